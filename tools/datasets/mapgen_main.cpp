// slamer-mapgen: a map_server map from a log's LIDAR scans at its reference poses.
#include <string>

#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "common/robot/robot_options.hpp"
#include "tools/datasets/occupancy_map.hpp"
#include "tools/datasets/wean_map.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-mapgen",
      "Builds an occupancy map from the LIDAR scans of an LCM log at its GROUND_TRUTH poses (exact at\n"
      "the scan's utime, or interpolated between two at most 0.5 s apart; other scans are skipped) by\n"
      "ray casting: a cell is occupied when at least a quarter of the beams that saw it ended in it.\n"
      "Writes map.pgm, semantic.png (walls as class 'others') and map.yaml into OUT_DIR, the format\n"
      "slamer-localizer loads (--map OUT_DIR/map.yaml). With --wean, converts the CMU 16-831 wean.dat[.gz]\n"
      "(P(free) per 10 cm cell, -1 unknown) given instead of LOG.lcm into the same format.",
      [](slamer::CommandLine& cli) {
        cli.set_positional("LOG.lcm OUT_DIR", "input log and output folder", 2, 2);
        cli.add_option("resolution", "M", "cell size [m]", "0.05");
        cli.add_option("robot", "FILE", "robot YAML whose lidar.mount places the laser (default: at the origin)");
        cli.add_option("lidar-channel", "NAME", "scan channel", "LIDAR");
        cli.add_option("pose-channel", "NAME", "reference pose channel", "GROUND_TRUTH");
        cli.add_flag("wean", "the input is the CMU Wean Hall wean.dat[.gz], not a log");
      },
      [](const slamer::CommandLine& cli) {
        slamer::MapgenOptions options;
        options.resolution = cli.get_double("resolution");
        if (!(options.resolution > 0.0)) {
          throw slamer::CommandLineError("option '--resolution': expected a size > 0");
        }
        if (cli.has("robot")) {
          options.laser_mount = slamer::load_options<slamer::RobotOptions>(cli.get("robot")).lidar.mount;
        }
        const std::string log_path = cli.positional()[0];
        const std::string directory = cli.positional()[1];
        if (cli.has("wean")) {
          const slamer::GridCells wean = slamer::read_wean_map(log_path);
          slamer::write_grid_map(wean.geometry, wean.cells, "Converted by slamer-mapgen --wean from " + log_path,
                                 directory);
          slamer::log_line("slamer-mapgen", slamer::LogLevel::kInfo, directory + "/map.yaml: converted " + log_path);
          return 0;
        }
        const slamer::ScansAtPoses data = slamer::read_scans_at_poses(log_path, cli.get("lidar-channel"),
                                                                      cli.get("pose-channel"), options.max_pose_gap);
        if (data.scans.empty()) {
          throw std::runtime_error("no scans with a " + cli.get("pose-channel") + " pose in " + log_path);
        }
        const slamer::OccupancyCounts counts = slamer::build_occupancy(data.scans, data.poses, options);
        slamer::write_occupancy_map(counts, options, directory);
        slamer::log_line("slamer-mapgen", slamer::LogLevel::kInfo,
                         directory + "/map.yaml: " + std::to_string(counts.geometry.width) + " x " +
                             std::to_string(counts.geometry.height) + " cells from " +
                             std::to_string(data.scans.size()) + " scans (" + std::to_string(data.scans_without_pose) +
                             " without a pose skipped)");
        return 0;
      });
}

// slamer-localizer: LIDAR + ODOMETRY + LINE_OBJECTS in; POSE, SEMANTIC_OBJECTS
// and PARTICLES out. Live on LCM, or offline from a log (--replay IN --out OUT);
// the wiring is localizer_process.hpp's, the same for both.
#include <sys/resource.h>

#include <cstdio>

#include "common/map/semantic_map.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "common/robot/robot_options.hpp"
#include "localizer/localizer_process.hpp"

namespace slamer {
namespace {

RobotOptions load_robot(const LocalizerProcessConfig& config) {
  return config.robot.empty() ? RobotOptions{} : load_options<RobotOptions>(config.robot);
}

// The node with the map's fields built; the map itself is freed on return.
LocalizerNode make_node(const LocalizerProcessConfig& config) {
  if (config.map.empty()) {
    throw ConfigError("no map: set 'map' in the config or pass --map");
  }
  const SemanticMap map = load_semantic_map(config.map);
  for (const std::string& warning : map.warnings) {
    log_line("slamer-localizer", LogLevel::kWarning, warning);
  }
  LocalizerNode node(map, config.localizer, load_robot(config).lidar.mount);
  char line[200];
  std::snprintf(line, sizeof line, "map %d x %d cells at %.3f m: distance fields %.1f MB", map.geometry.width,
                map.geometry.height, map.geometry.resolution, static_cast<double>(node.map_memory_bytes()) / 1e6);
  log_line("slamer-localizer", LogLevel::kInfo, line);
  return node;
}

// The config with the command line's overrides.
LocalizerProcessConfig configure(const CommandLine& cli) {
  auto config = load_config<LocalizerProcessConfig>(cli);
  if (cli.has("mode")) {
    try {
      config.localizer.mode = parse_mode(cli.get("mode"));
    } catch (const std::invalid_argument& e) {
      throw CommandLineError(std::string("option '--mode': ") + e.what());
    }
  }
  if (cli.has("seed")) {
    const int64_t seed = cli.get_int("seed");
    if (seed < 0) {
      throw CommandLineError("option '--seed': expected a number >= 0");
    }
    config.localizer.seed = static_cast<uint64_t>(seed);
  }
  if (cli.has("map")) {
    config.map = cli.get("map");
  }
  if (cli.has("robot")) {
    config.robot = cli.get("robot");
  }
  if (cli.has("pose-file")) {
    config.pose_file = cli.get("pose-file");
  }
  config.start_global = cli.has("global");
  if (cli.has("initial-pose")) {
    const std::vector<double> pose = cli.get_doubles("initial-pose");
    config.localizer.initial_pose = {pose[0], pose[1], pose[2]};
  }
  return config;
}

int run(const CommandLine& cli) {
  const LocalizerProcessConfig config = configure(cli);
  LocalizerNode node = make_node(config);
  const std::unique_ptr<Bus> bus = open_bus(cli, "slamer-localizer", config.process);
  LocalizerProcess process(*bus, config, load_robot(config), std::move(node), bus->is_live());
  const int code = bus->run();
  const NodeCounters& c = process.node().counters();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  bus->log_info(std::to_string(process.scans_published()) + " scans localized (" +
                std::to_string(c.scans_without_objects) + " without objects, " +
                std::to_string(c.scans_without_odometry) + " without odometry, " + std::to_string(c.stale_scans) +
                " stale, " + std::to_string(c.resets) + " resets; objects: " + std::to_string(c.stale_objects) +
                " late, " + std::to_string(c.objects_without_scan) + " for scans that never came, " +
                std::to_string(c.objects_before_scan) + " before their scan); peak resident " +
                std::to_string(usage.ru_maxrss / 1024) + " MB");
  return code;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-localizer",
      "SLAMER: localization and map-assisted environment recognition with a particle filter. Publishes\n"
      "POSE, SEMANTIC_OBJECTS and PARTICLES. --mode lfm|slfm|slamer picks the measurement model;\n"
      "--replay IN --out OUT runs offline on a log, as fast as it can, the same for the same seed.",
      [](slamer::CommandLine& cli) {
        cli.add_option("mode", "MODE", "lfm, slfm or slamer (overrides the config)");
        cli.add_option("seed", "N", "random seed (overrides the config)");
        cli.add_option("map", "FILE", "semantic map YAML (overrides the config)");
        cli.add_option("robot", "FILE", "robot YAML, for the LiDAR mount (overrides the config)");
        cli.add_option("pose-file", "FILE", "keep the last good pose here and resume from it (overrides the config)");
        cli.add_multi_option("initial-pose", 3, "X Y THETA", "start here [m, m, rad] (overrides the config)");
        cli.add_flag("global", "start with global localization: the robot may be anywhere on the map");
        slamer::add_replay_options(cli, "POSE, SEMANTIC_OBJECTS and PARTICLES");
      },
      slamer::run);
}

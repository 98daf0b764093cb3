// slamer-bench: the real-log protocol on a *-corrected CARMEN log: import,
// map, offline localization with the real slamer-localizer, scoring.
#include <chrono>
#include <filesystem>
#include <optional>
#include <utility>

#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "tools/datasets/bench_files.hpp"
#include "tools/datasets/dataset_lcm.hpp"
#include "tools/datasets/occupancy_map.hpp"
#include "tools/datasets/run_program.hpp"

namespace slamer {
namespace {

int bench(const CommandLine& cli) {
  const std::string log_path = cli.get("carmen");
  const std::filesystem::path dir = std::filesystem::absolute(cli.get("out"));
  const int64_t particles = cli.get_int("particles");
  const std::string beams = cli.get("beams");
  if (particles < 1 || (beams != "all" && beams != "60") || cli.get_int("seed") < 0) {
    throw CommandLineError("--particles must be >= 1, --beams all or 60, --seed >= 0");
  }
  ImportOptions import;
  import.corrected = ImportOptions::Corrected::kYes;
  const ImportedLog whole = import_dataset(log_path, import);
  for (const std::string& error : whole.errors) {
    log_line("slamer-bench", LogLevel::kWarning, "malformed line skipped: " + error);
  }
  if (whole.scans.empty() || whole.reference.size() != whole.scans.size()) {
    throw std::runtime_error("no scans with corrected poses in " + log_path);
  }
  log_line("slamer-bench", LogLevel::kInfo, log_path + ": " + describe_import(whole));
  const std::optional<std::pair<std::size_t, std::size_t>> carry =
      cli.has("kidnap") ? std::optional(kidnap_scans(cli.get_doubles("kidnap"), whole.scans.size())) : std::nullopt;
  // The map from every scan; the localizer sees the kidnapped log.
  const ImportedLog log = carry ? kidnapped(whole, carry->first, carry->second) : whole;
  if (carry) {
    log_line("slamer-bench", LogLevel::kInfo, describe_kidnap(whole, log, carry->first));
  }
  std::filesystem::create_directories(dir);
  write_dataset_lcm(log, (dir / "input.lcm").string());
  const Pose2 mount = log.laser_mount.value_or(Pose2{});
  MapgenOptions map_options;
  map_options.resolution = 0.05;
  map_options.laser_mount = mount;
  write_occupancy_map(build_occupancy(whole.scans, whole.reference, map_options), map_options, dir.string());
  write_text_file((dir / "robot.yaml").string(), dataset_robot_yaml(log_path, log.scans.front(), mount));
  const int beam_step = beams == "all" ? 1 : std::max(1, static_cast<int>(log.scans.front().ranges.size() / 60));
  BenchConfigChanges changes{static_cast<int>(particles), beam_step, (dir / "map.yaml").string(),
                             (dir / "robot.yaml").string()};
  write_text_file((dir / "localizer.yaml").string(), bench_localizer_config(cli.get("localizer-config"), changes));

  const Pose2 start = log.reference.front();
  const bool global = cli.has("global");
  const std::string localizer =
      cli.get("localizer").empty()
          ? (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "slamer-localizer").string()
          : cli.get("localizer");
  const BenchLocalizerRun run_setup{
      (dir / "localizer.yaml").string(),           changes.map, changes.robot, cli.get("mode"), cli.get("seed"),
      global ? std::nullopt : std::optional(start)};
  const auto args = bench_localizer_args(run_setup, (dir / "input.lcm").string(), (dir / "localized.lcm").string());
  BenchRunInfo info;
  info.log = log_path;
  info.mode = cli.get("mode");
  info.particles = static_cast<int>(particles);
  info.beams = beams;
  info.seed = cli.get_int("seed");
  info.global = global;
  info.kidnap = carry;
  info.command = localizer;
  for (const std::string& a : args) {
    info.command += " " + a;
  }
  log_line("slamer-bench", LogLevel::kInfo, "running " + info.command);
  const auto wall_start = std::chrono::steady_clock::now();
  const ProgramRun run = run_program(localizer, args);
  info.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  info.cpu_seconds = run.cpu_seconds;
  // What starting up costs (map loading, field building): the same run on the first scan alone.
  write_dataset_lcm(first_scan_only(log), (dir / "startup.lcm").string());
  const ProgramRun startup = run_program(
      localizer, bench_localizer_args(run_setup, (dir / "startup.lcm").string(), (dir / "startup_out.lcm").string()));
  info.startup_cpu_seconds = startup.cpu_seconds;
  if (run.exit_code != 0 || startup.exit_code != 0) {
    throw std::runtime_error(localizer + " failed with exit code " + std::to_string(run.exit_code));
  }

  int64_t missing = 0;
  const std::vector<BenchPose> poses = poses_per_scan(
      log, read_pose_reports((dir / "localized.lcm").string(), cli.get("pose-channel")), start, &missing);
  const BenchScore score = score_poses(poses, log.reference);
  write_text_file((dir / "poses.txt").string(),
                  format_poses(carry ? with_carried_scans(poses, whole, carry->first, carry->second) : poses));
  write_text_file((dir / "summary.json").string(), summary_json(score, info));
  write_bench_plot(poses, score, std::filesystem::path(log_path).filename().string(), (dir / "errors.png").string());
  if (missing > 0) {
    log_line("slamer-bench", LogLevel::kWarning,
             std::to_string(missing) + " scans had no POSE: poses.txt repeats the previous pose for them");
  }
  log_line("slamer-bench", LogLevel::kInfo, describe_score(score, info) + "; " + (dir / "summary.json").string());
  if (global || carry) {
    log_line("slamer-bench", LogLevel::kInfo,
             std::string(global ? "global localization" : "after the kidnap") + ": " + describe_right_from(score));
  }
  return 0;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-bench",
      "Runs the real-log protocol on a *-corrected CARMEN log: import (raw odometry rebuilt from the\n"
      "re-anchored ODOM lines) into OUT/input.lcm, a 5 cm map (OUT/map.yaml), slamer-localizer offline\n"
      "from the first corrected pose (or --global), then scoring against the corrected poses (GMapping's,\n"
      "not ground truth): OUT/poses.txt (`t x y theta status` per scan, t the log's time; a scan without\n"
      "a POSE repeats the previous pose), OUT/summary.json, OUT/errors.png. --kidnap FROM TO leaves\n"
      "scans FROM to TO - 1 out and hides the carry from the odometry; poses.txt repeats the pose before\n"
      "the carry for them, the scores count the scans kept.",
      [](slamer::CommandLine& cli) {
        cli.add_option("carmen", "LOG", "*-corrected CARMEN log (.gz or plain)");
        cli.add_option("out", "DIR", "output folder");
        cli.add_option("particles", "N", "particles", "500");
        cli.add_option("beams", "all|60", "every beam, or about 60 (the localizer's beam_step)", "all");
        cli.add_option("mode", "MODE", "lfm, slfm or slamer", "lfm");
        cli.add_option("seed", "S", "localizer seed", "1");
        cli.add_flag("global", "start with global localization instead of at the first corrected pose");
        cli.add_multi_option("kidnap", 2, "FROM TO",
                             "carry the robot unseen from scan FROM to scan TO (leaving out the scans between; "
                             "the map keeps them)");
        cli.add_option("localizer-config", "FILE", "base localizer config", "config/localizer.yaml");
        cli.add_option("localizer", "PROGRAM", "slamer-localizer to run (default: the one beside this program)");
        cli.add_option("pose-channel", "NAME", "the localizer's pose channel", "POSE");
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("carmen") || !cli.has("out")) {
          throw slamer::CommandLineError("--carmen LOG and --out DIR are required");
        }
        return slamer::bench(cli);
      });
}

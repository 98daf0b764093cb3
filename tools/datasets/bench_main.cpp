// slamer-bench: the real-log protocol on a *-corrected CARMEN log: import,
// map, offline localization with the real slamer-localizer, scoring.
#include <chrono>
#include <filesystem>

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
  const ImportedLog log = import_dataset(log_path, import);
  for (const std::string& error : log.errors) {
    log_line("slamer-bench", LogLevel::kWarning, "malformed line skipped: " + error);
  }
  if (log.scans.empty() || log.reference.size() != log.scans.size()) {
    throw std::runtime_error("no scans with corrected poses in " + log_path);
  }
  log_line("slamer-bench", LogLevel::kInfo, log_path + ": " + describe_import(log));
  std::filesystem::create_directories(dir);
  write_dataset_lcm(log, (dir / "input.lcm").string());
  const Pose2 mount = log.laser_mount.value_or(Pose2{});
  MapgenOptions map_options;
  map_options.resolution = 0.05;
  map_options.laser_mount = mount;
  write_occupancy_map(build_occupancy(log.scans, log.reference, map_options), map_options, dir.string());
  write_text_file((dir / "robot.yaml").string(), dataset_robot_yaml(log_path, log.scans.front(), mount));
  const int beam_step = beams == "all" ? 1 : std::max(1, static_cast<int>(log.scans.front().ranges.size() / 60));
  BenchConfigChanges changes{static_cast<int>(particles), beam_step, (dir / "map.yaml").string(),
                             (dir / "robot.yaml").string()};
  write_text_file((dir / "localizer.yaml").string(), bench_localizer_config(cli.get("localizer-config"), changes));

  const Pose2 start = log.reference.front();
  std::string localizer = cli.get("localizer");
  if (localizer.empty()) {
    localizer = (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "slamer-localizer").string();
  }
  const auto args_for = [&](const std::string& in, const std::string& out) {
    std::vector<std::string> args{
        "--config",      (dir / "localizer.yaml").string(), "--map", changes.map, "--robot", changes.robot,
        "--initial-pose"};
    for (const double v : {start.x, start.y, start.theta}) {
      args.push_back(std::to_string(v));
    }
    args.insert(args.end(), {"--mode", cli.get("mode"), "--seed", cli.get("seed"), "--replay", in, "--out", out});
    return args;
  };
  const auto args = args_for((dir / "input.lcm").string(), (dir / "localized.lcm").string());
  BenchRunInfo info{
      log_path, cli.get("mode"), static_cast<int>(particles), beams, cli.get_int("seed"), 0.0, 0.0, localizer, 0.0};
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
  const ProgramRun startup =
      run_program(localizer, args_for((dir / "startup.lcm").string(), (dir / "startup_out.lcm").string()));
  info.startup_cpu_seconds = startup.cpu_seconds;
  if (run.exit_code != 0 || startup.exit_code != 0) {
    throw std::runtime_error(localizer + " failed with exit code " + std::to_string(run.exit_code));
  }

  std::vector<int64_t> utimes;
  std::vector<int64_t> log_utimes;
  for (const LaserScan& scan : log.scans) {
    utimes.push_back(scan.utime);
    log_utimes.push_back(scan.sensor_utime);
  }
  int64_t missing = 0;
  const std::vector<BenchPose> poses =
      poses_per_scan(utimes, log_utimes, read_pose_reports((dir / "localized.lcm").string(), cli.get("pose-channel")),
                     start, &missing);
  const BenchScore score = score_poses(poses, log.reference);
  write_text_file((dir / "poses.txt").string(), format_poses(poses));
  write_text_file((dir / "summary.json").string(), summary_json(score, info));
  write_bench_plot(poses, score, std::filesystem::path(log_path).filename().string(), (dir / "errors.png").string());
  if (missing > 0) {
    log_line("slamer-bench", LogLevel::kWarning,
             std::to_string(missing) + " scans had no POSE: poses.txt repeats the previous pose for them");
  }
  char text[400];
  std::snprintf(text, sizeof text,
                "%lld scans: position error mean %.1f cm (std %.1f, max %.1f), heading %.2f deg, lost %.1f %%, "
                "status: %.1f %% of %lld far flagged after 2 s, %.2f %% of close LOST, "
                "%.3f ms per scan (CPU, start-up excluded); %s",
                static_cast<long long>(score.scans), score.position.mean * 100, score.position.std * 100,
                score.position.max * 100, score.heading.mean * 180 / 3.14159265358979, score.fraction_lost * 100,
                score.honesty.far_flagged_fraction() * 100, static_cast<long long>(score.honesty.far_after_grace()),
                score.honesty.close_lost_fraction() * 100,
                std::max(0.0, info.cpu_seconds - info.startup_cpu_seconds) / std::max<double>(1, score.scans - 1) * 1e3,
                (dir / "summary.json").c_str());
  log_line("slamer-bench", LogLevel::kInfo, text);
  return 0;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-bench",
      "Runs the real-log protocol on a *-corrected CARMEN log: imports it (slamer-carmen2lcm's rules,\n"
      "raw odometry rebuilt from the re-anchored ODOM lines) into OUT/input.lcm, builds a 5 cm map from\n"
      "the scans at the corrected poses (OUT/map.yaml), runs slamer-localizer offline from the first\n"
      "corrected pose, and scores every scan against the corrected poses (GMapping's estimate, not\n"
      "ground truth). Writes OUT/poses.txt (`t x y theta status` per scan, t the log's time; a scan\n"
      "without a POSE repeats the previous pose), OUT/summary.json and OUT/errors.png.",
      [](slamer::CommandLine& cli) {
        cli.add_option("carmen", "LOG", "*-corrected CARMEN log (.gz or plain)");
        cli.add_option("out", "DIR", "output folder");
        cli.add_option("particles", "N", "particles", "500");
        cli.add_option("beams", "all|60", "every beam, or about 60 (the localizer's beam_step)", "all");
        cli.add_option("mode", "MODE", "lfm, slfm or slamer", "lfm");
        cli.add_option("seed", "S", "localizer seed", "1");
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

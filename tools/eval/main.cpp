// slamer-eval: scores logs against the simulation's ground truth (the paper's table).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/semantic_objects_t.hpp"
#include "tools/eval/eval_config.hpp"
#include "tools/eval/report.hpp"

namespace slamer {
namespace {

// Reads what scoring needs from a log. `estimate` names the channel of the
// estimate; ODOMETRY is placed in the map by the first ground-truth pose.
RunInputs read_run(const std::string& path, const EvalChannels& channels, const std::string& estimate) {
  EventLogReader log(path);
  RunInputs run;
  std::vector<PoseSample> odometry;
  std::map<std::string, int64_t> errors;
  const auto decode = [&](const std::optional<LogEvent>& event, auto* message) {
    const DecodeStatus status = decode_message(event->data.data(), event->data.size(), message);
    if (status != DecodeStatus::kOk) {
      ++errors[event->channel];
    }
    return status == DecodeStatus::kOk;
  };
  const bool terminal = isatty(STDERR_FILENO) != 0;
  int64_t events = 0;
  while (const std::optional<LogEvent> event = log.next()) {
    if (terminal && ++events % 20000 == 0) {
      std::fprintf(stderr, "\rslamer-eval: reading %s %3.0f%%", path.c_str(), 100.0 * log.fraction_read());
    }
    const std::string& channel = event->channel;
    if (channel == channels.ground_truth || (channel == estimate && estimate != channels.odometry)) {
      pose_estimate_t pose{};
      if (decode(event, &pose)) {
        const PoseSample sample{pose.utime, {pose.x, pose.y, pose.theta}};
        if (channel == channels.ground_truth) {
          run.truth.push_back(sample);
        }
        if (channel == estimate) {  // GROUND_TRUTH as the estimate checks the tool itself
          run.estimate.push_back(sample);
        }
      }
    } else if (channel == channels.odometry && estimate == channels.odometry) {
      odometry_t odom{};
      if (decode(event, &odom)) {
        odometry.push_back({odom.utime, {odom.x, odom.y, odom.theta}});
      }
    } else if (channel == channels.line_objects) {
      line_objects_t objects{};
      if (decode(event, &objects)) {
        run.recognized.push_back(from_message(objects));
      }
    } else if (channel == channels.semantic_objects) {
      semantic_objects_t objects{};
      if (decode(event, &objects)) {
        run.semantic.push_back(from_message(objects));
      }
    }
  }
  if (terminal && events >= 20000) {
    std::fprintf(stderr, "\n");
  }
  if (!log.problems().empty()) {
    log_line("slamer-eval", LogLevel::kWarning, log.problems());
  }
  for (const auto& [channel, count] : errors) {
    log_line("slamer-eval", LogLevel::kWarning,
             path + ": " + std::to_string(count) + " messages on " + channel + " did not decode; skipped");
  }
  const auto by_time = [](const PoseSample& a, const PoseSample& b) { return a.utime < b.utime; };
  std::stable_sort(run.truth.begin(), run.truth.end(), by_time);
  if (estimate == channels.odometry) {
    // Dead reckoning at every scan time, placed in the map where the first
    // ground-truth pose inside the odometry's time span says the robot was.
    std::stable_sort(odometry.begin(), odometry.end(), by_time);
    std::optional<Pose2> odom_to_map;
    for (const PoseSample& truth : run.truth) {
      const std::optional<Pose2> odom = pose_at(odometry, truth.utime);
      if (!odom) {
        continue;
      }
      if (!odom_to_map) {
        odom_to_map = compose(truth.pose, inverse(*odom));
      }
      run.estimate.push_back({truth.utime, compose(*odom_to_map, *odom)});
    }
  }
  std::stable_sort(run.estimate.begin(), run.estimate.end(), by_time);
  if (run.truth.empty()) {
    log_line("slamer-eval", LogLevel::kWarning, path + ": no " + channels.ground_truth + " messages");
  }
  return run;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-eval",
      "Scores logs of a simulated run against its ground truth, as in the paper's table: position and\n"
      "heading error Ave/Std/Max, time lost, and recognition accuracy Ave/Std/Min/Max of the recognizer\n"
      "alone, the simple map-based method and SLAMER. Several logs are shown side by side.",
      [](slamer::CommandLine& cli) {
        cli.add_option("world", "FILE", "the world file the logs were simulated in");
        cli.add_option("estimate", "CHANNEL", "channel of the estimate: POSE, GROUND_TRUTH or ODOMETRY", "POSE");
        cli.add_option("plot", "FILE.png", "also draw the position error over time");
        cli.add_flag("json", "print JSON instead of the table");
        cli.set_positional("LOG", "LCM logs to score", 1, 32);
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("world")) {
          throw slamer::CommandLineError("--world FILE is required");
        }
        const auto config = slamer::load_config<slamer::EvalConfig>(cli);
        const std::string world_file = cli.get("world");
        const auto world_options = slamer::load_options<slamer::WorldOptions>(world_file);
        const auto robot = slamer::load_options<slamer::RobotOptions>(world_options.robot_path);
        const slamer::SemanticMap map = slamer::load_semantic_map(world_options.map_path);
        const slamer::TrueWorld truth_world(map, world_options, world_file);
        slamer::WorldOptions as_mapped = world_options;
        as_mapped.doors.clear();
        as_mapped.objects.clear();
        const slamer::TrueWorld map_world(map, as_mapped, world_file);

        std::vector<slamer::NamedRun> runs;
        for (const std::string& path : cli.positional()) {
          const slamer::RunInputs inputs = slamer::read_run(path, config.channels, cli.get("estimate"));
          runs.push_back({std::filesystem::path(path).filename().string(),
                          slamer::score_run(inputs, truth_world, map_world, robot.lidar.mount, config.eval)});
        }
        std::cout << (cli.has("json") ? slamer::render_json(runs, config.eval)
                                      : slamer::render_table(runs, config.eval));
        if (cli.has("plot")) {
          slamer::write_error_plot(runs, cli.get("plot"));
        }
        return 0;
      });
}

#include "tools/eval/run_log.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/semantic_objects_t.hpp"

namespace slamer {

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
        // A status this tool does not know: no status figures for the run.
        const PoseSample sample{pose.utime, {pose.x, pose.y, pose.theta}, reported_status(pose.status)};
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

}  // namespace slamer

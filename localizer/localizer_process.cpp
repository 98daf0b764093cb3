#include "localizer/localizer_process.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>

#include "common/process/convert.hpp"
#include "localizer/localizer_messages.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/semantic_objects_t.hpp"

namespace slamer {

namespace {

InputLimits limits_of(const RobotOptions& robot) {
  InputLimits limits;
  limits.max_beams = robot.lidar.beams;
  limits.max_speed = robot.base.max_speed;
  limits.max_yaw_rate = robot.base.max_yaw_rate;
  return limits;
}

}  // namespace

LocalizerProcess::LocalizerProcess(Bus& bus, const LocalizerProcessConfig& config, const RobotOptions& robot,
                                   LocalizerNode node, bool keep_pose)
    : bus_(bus),
      config_(config),
      node_(std::move(node)),
      pose_keeper_(keep_pose ? config.pose_file : ""),
      limits_(limits_of(robot)),
      scan_time_(limits_),
      odometry_time_(limits_),
      last_particles_utime_(std::numeric_limits<int64_t>::min() / 2) {
  const LocalizerChannels& ch = config_.channels;
  std::string note;
  if (const std::optional<SavedPose> saved = pose_keeper_.load(&note)) {
    node_.resume(saved->pose, saved->sigma, saved->utime);
  }
  if (!note.empty()) {
    bus_.log_info(note);
  }
  if (config_.start_global) {
    node_.request_global_localization();
    bus_.log_info("global localization from the start: particles over the map's free space");
  }
  bus_.subscribe<odometry_t>(ch.odometry, [this](const odometry_t& m, const ReceiveInfo&) { on_odometry(m); });
  bus_.subscribe<laser_scan_t>(ch.lidar, [this](const laser_scan_t& m, const ReceiveInfo&) { on_scan(m); });
  bus_.subscribe<line_objects_t>(ch.line_objects, [this](const line_objects_t& m, const ReceiveInfo&) {
    node_.on_objects(from_message(m));
    publish_ready();
  });
  bus_.subscribe<initial_pose_t>(ch.initial_pose,
                                 [this](const initial_pose_t& m, const ReceiveInfo&) { on_initial_pose(m); });
  for (const std::string& output : {ch.pose, ch.semantic_objects, ch.particles}) {
    bus_.advertise(output);
  }
  // The node counts what it refuses; the status reads its counters.
  const auto drops = [this](auto count) { return [this, count] { return count(node_.counters()); }; };
  ProcessHealth& health = bus_.health();
  health.add_drop_source(ch.lidar, channel_stats_t::SUBSCRIBED,
                         drops([](const NodeCounters& c) { return c.stale_scans; }));
  health.add_drop_source(ch.odometry, channel_stats_t::SUBSCRIBED,
                         drops([](const NodeCounters& c) { return c.stale_odometry + c.invalid_odometry; }));
  health.add_drop_source(ch.line_objects, channel_stats_t::SUBSCRIBED,
                         drops([](const NodeCounters& c) { return c.stale_objects + c.objects_without_scan; }));
  health.add_drop_source(ch.initial_pose, channel_stats_t::SUBSCRIBED,
                         drops([](const NodeCounters& c) { return c.invalid_initial_poses; }));
  for (const std::string& input : {ch.lidar, ch.odometry, ch.initial_pose}) {
    health.add_drop_source(input, channel_stats_t::SUBSCRIBED, [this, input] { return refused_.total(input); });
  }
  bus_.every(1.0, [this] {
    if (const std::string summary = refused_.take_summary(); !summary.empty()) {
      bus_.log_warning(summary);
    }
    // Objects of scans we do not have, beyond the scans we refused: the
    // recognizer had them and we did not, datagrams lost to us (a full receive
    // buffer: see net.core.rmem_max in the README).
    const int64_t lost = node_.counters().objects_without_scan - refused_.total(config_.channels.lidar);
    if (lost > scans_lost_said_) {
      bus_.log_warning("at least " + std::to_string(lost - scans_lost_said_) + " scans on " + config_.channels.lidar +
                       " never reached us (their " + config_.channels.line_objects + " did)");
      scans_lost_said_ = lost;
    }
  });

  // A scan whose objects do not come is processed without them after objects_wait.
  bus_.every(0.01, [this] { publish_ready(); });
  const int64_t start = bus_.now();
  // Checked 4x per timeout, so the gap is said at most a quarter of it late.
  bus_.every(std::clamp(config_.localizer.inputs.scan_timeout / 4.0, 0.01, 1.0), [this, start] {
    if (node_.scans_missing(bus_.now(), start)) {
      char text[96];
      std::snprintf(text, sizeof text, "no scans on %s for %.1f s: no pose", config_.channels.lidar.c_str(),
                    config_.localizer.inputs.scan_timeout);
      bus_.set_state(process_status_t::DEGRADED, text);
    }
  });
  bus_.at_finish([this] {
    while (const std::optional<UpdateResult> result = node_.poll(std::numeric_limits<int64_t>::max())) {
      publish(*result);
    }
    save_pose();  // a clean stop keeps the very last good pose
  });
  if (pose_keeper_.enabled()) {
    bus_.every(config_.pose_save_period, [this] { save_pose(); });
  }
}

void LocalizerProcess::refuse(const std::string& channel, const std::string& reason) {
  refused_.count(channel, reason);
}

void LocalizerProcess::on_scan(const laser_scan_t& message) {
  const LaserScan scan = from_message(message);
  if (const std::string problem = scan_problem(scan, limits_); !problem.empty()) {
    refuse(config_.channels.lidar, problem);
    return;
  }
  const auto refuse_held = [this] {
    for (const auto& [held, arrival] : held_scans_) {
      refuse(config_.channels.lidar, "utime far from the stream's (" + std::to_string(held.utime) + ")");
    }
    held_scans_.clear();
  };
  switch (scan_time_.check(scan.utime)) {
    case TimeVerdict::kRefuse:
      if (scan_time_.agreeing() == 1) {
        refuse_held();  // the ones before did not agree with this one
      }
      held_scans_.emplace_back(scan, bus_.now());
      return;
    case TimeVerdict::kMoved:
      bus_.log_warning(config_.channels.lidar + "'s time moved to " + std::to_string(scan.utime) +
                       " (several scans agree): following it");
      for (const auto& [held, arrival] : held_scans_) {
        node_.on_scan(held, arrival);
      }
      held_scans_.clear();
      break;
    case TimeVerdict::kAccept:
      refuse_held();
      break;
  }
  if (const std::string restart = scan_restart_.check(message.seq, scan.utime); !restart.empty()) {
    // Scans stand alone: nothing to start over; said, as a gap in the input.
    bus_.note_event(process_status_t::DEGRADED, config_.channels.lidar + "'s driver restarted (" + restart + ")");
  }
  // The wait for its objects counts from now, when this process takes the scan
  // off its queue, not from when it reached the host: a localizer that fell
  // behind (a slow build, a busy CPU) would otherwise find every scan's wait
  // over as it reads it, with the objects next in its queue.
  node_.on_scan(scan, bus_.now());
  publish_ready();
}

void LocalizerProcess::on_odometry(const odometry_t& m) {
  const std::string& channel = config_.channels.odometry;
  const Pose2 pose{m.x, m.y, m.theta};
  if (!std::isfinite(m.x) || !std::isfinite(m.y) || !std::isfinite(m.theta) || m.utime <= 0) {
    refuse(channel, "not a finite pose at a time");  // one NaN would carry into every particle
    return;
  }
  const auto refuse_held = [&] {
    for (const auto& [utime, held] : held_odometry_) {
      refuse(channel, "utime far from the stream's (" + std::to_string(utime) + ")");
    }
    held_odometry_.clear();
  };
  switch (odometry_time_.check(m.utime)) {
    case TimeVerdict::kRefuse:
      if (odometry_time_.agreeing() == 1) {
        refuse_held();
      }
      held_odometry_.emplace_back(m.utime, pose);
      return;
    case TimeVerdict::kMoved:
      bus_.log_warning(channel + "'s time moved to " + std::to_string(m.utime) +
                       " (several messages agree): a new reference");
      node_.restart_odometry();
      odometry_restart_.check(m.seq, m.utime);  // a new reference already
      for (const auto& [utime, held] : held_odometry_) {
        node_.on_odometry(utime, held);
      }
      held_odometry_.clear();
      break;
    case TimeVerdict::kAccept:
      refuse_held();
      if (const std::string restart = odometry_restart_.check(m.seq, m.utime); !restart.empty()) {
        bus_.note_event(process_status_t::DEGRADED,
                        channel + "'s driver restarted (" + restart + "): its frame is new, a new reference");
        node_.restart_odometry();
      } else if (last_odometry_) {
        const auto& [from_utime, from] = *last_odometry_;
        if (const std::string jump = odometry_step_problem(from, from_utime, pose, m.utime, limits_); !jump.empty()) {
          refuse(channel, jump + ": not integrated, a new reference");
          node_.restart_odometry();
        }
      }
      break;
  }
  last_odometry_ = {m.utime, pose};
  node_.on_odometry(m.utime, pose);
  publish_ready();  // a scan may have waited for odometry past its time
}

void LocalizerProcess::on_initial_pose(const initial_pose_t& m) {
  const std::string& channel = config_.channels.initial_pose;
  std::array<double, 9> covariance{};
  std::copy(std::begin(m.cov), std::end(m.cov), covariance.begin());
  const Pose2 pose{m.x, m.y, m.theta};
  // cov[0] < 0 asks for global localization (initial_pose_t.lcm); x, y, theta are then ignored.
  const bool global = std::isfinite(m.cov[0]) && m.cov[0] < 0.0;
  std::string problem =
      global ? "" : initial_pose_problem(pose, covariance, std::isfinite(m.x) && node_.on_map(m.x, m.y));
  if (problem.empty() && last_initial_pose_ &&
      bus_.now() - *last_initial_pose_ < static_cast<int64_t>(limits_.initial_pose_period * 1e6)) {
    problem = "more than one per " + std::to_string(limits_.initial_pose_period).substr(0, 3) + " s";
  }
  if (!problem.empty()) {
    refuse(channel, problem);
    return;
  }
  if (global) {
    node_.request_global_localization();
    last_initial_pose_ = bus_.now();
    bus_.log_info("global localization requested: particles over the map's free space");
    return;
  }
  if (!node_.on_initial_pose(pose, sigma_of_covariance(m.cov))) {
    return;  // counted by the node
  }
  last_initial_pose_ = bus_.now();
  bus_.log_info("initial pose set: " + describe(m));
}

void LocalizerProcess::publish_ready() {
  // Only scans actually processed count toward the processing time p50/p99.
  for (auto start = std::chrono::steady_clock::now();; start = std::chrono::steady_clock::now()) {
    const std::optional<UpdateResult> result = node_.poll(bus_.now());
    if (!result) {
      break;
    }
    if (bus_.is_live()) {
      bus_.record_processing_time(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    publish(*result);
  }
}

void LocalizerProcess::publish(const UpdateResult& result) {
  const int64_t utime = result.semantic.utime;
  bus_.publish(config_.channels.pose, to_pose_message(result, utime, config_.localizer.particles));
  bus_.publish(config_.channels.semantic_objects, to_semantic_objects_message(result.semantic));
  if (config_.particles_out > 0 &&
      (utime - last_particles_utime_ >= static_cast<int64_t>(config_.particles_period * 1e6) ||
       utime < last_particles_utime_)) {  // time went back (a restart): PARTICLES go on
    bus_.publish(config_.channels.particles, to_particles_message(node_.particles(), utime, config_.particles_out));
    last_particles_utime_ = utime;
  }
  ++scans_published_;
  if (!resume_reported_ && node_.resumed()) {
    resume_reported_ = true;
    char text[160];
    std::snprintf(text, sizeof text, "down for %.1f s since the saved pose: %s until the scans confirm it",
                  node_.resumed()->downtime,
                  node_.resumed()->global ? "global localization" : "its sigma grown by that time, UNCERTAIN");
    bus_.log_info(text);
  }
  const auto [state, message] =
      process_state(result.estimate.status, result.estimate.status_reason, node_.health(), config_.channels);
  bus_.set_state(state, message);
  if (result.estimate.status == LocalizerStatus::kOk) {
    pose_keeper_.offer(
        SavedPose{result.semantic.utime, result.estimate.pose, sigma_of_covariance(result.estimate.covariance)});
  }
}

void LocalizerProcess::save_pose() {
  try {
    pose_keeper_.save();
  } catch (const std::runtime_error& e) {
    bus_.count_error(e.what());  // summarized in the log, rate-limited
  }
}

}  // namespace slamer

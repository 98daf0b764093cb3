#include "localizer/localizer_process.hpp"

#include <chrono>
#include <limits>

#include "common/process/convert.hpp"
#include "localizer/localizer_messages.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/semantic_objects_t.hpp"

namespace slamer {

LocalizerProcess::LocalizerProcess(Bus& bus, const LocalizerProcessConfig& config, LocalizerNode node, bool keep_pose)
    : bus_(bus),
      config_(config),
      node_(std::move(node)),
      pose_keeper_(keep_pose ? config.pose_file : ""),
      last_particles_utime_(std::numeric_limits<int64_t>::min() / 2) {
  const LocalizerChannels& ch = config_.channels;
  std::string note;
  if (const std::optional<SavedPose> saved = pose_keeper_.load(&note)) {
    node_.on_initial_pose(saved->pose, saved->sigma);
  }
  if (!note.empty()) {
    bus_.log_info(note);
  }
  bus_.subscribe<odometry_t>(ch.odometry, [this](const odometry_t& m, const ReceiveInfo&) {
    node_.on_odometry(m.utime, {m.x, m.y, m.theta});
  });
  bus_.subscribe<laser_scan_t>(ch.lidar, [this](const laser_scan_t& m, const ReceiveInfo& info) {
    node_.on_scan(from_message(m), info.receive_utime);
    publish_ready();
  });
  bus_.subscribe<line_objects_t>(ch.line_objects, [this](const line_objects_t& m, const ReceiveInfo&) {
    node_.on_objects(from_message(m));
    publish_ready();
  });
  bus_.subscribe<initial_pose_t>(ch.initial_pose, [this](const initial_pose_t& m, const ReceiveInfo&) {
    if (!node_.on_initial_pose({m.x, m.y, m.theta}, sigma_of_covariance(m.cov))) {
      bus_.log_warning("INITIAL_POSE ignored: " + describe(m));
      return;
    }
    bus_.log_info("initial pose set: " + describe(m));
  });
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
                         drops([](const NodeCounters& c) { return c.stale_objects; }));
  health.add_drop_source(ch.initial_pose, channel_stats_t::SUBSCRIBED,
                         drops([](const NodeCounters& c) { return c.invalid_initial_poses; }));

  // A scan whose objects do not come is processed without them after objects_wait.
  bus_.every(0.01, [this] { publish_ready(); });
  const int64_t start = bus_.now();
  bus_.every(1.0, [this, start] {
    if (node_.scans_missing(bus_.now(), start)) {
      char text[96];
      std::snprintf(text, sizeof text, "no scans on %s for %.1f s: no pose", config_.channels.lidar.c_str(),
                    config_.localizer.scan_timeout);
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
  const auto [state, message] = process_state(result.estimate.status, node_.health(), config_.channels);
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

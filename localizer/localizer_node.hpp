// What a running localizer does around the filter: keeps odometry to
// interpolate it to each scan's time, pairs each scan with its recognized
// objects (waiting a little for them), drops stale or out-of-order input,
// and starts over when time jumps backwards (a log replayed from the top).
// No clock and no LCM: times come with the inputs; `now` is passed in.
#pragma once

#include <deque>
#include <optional>

#include "localizer/particle_filter.hpp"

namespace slamer {

struct NodeCounters {
  int64_t stale_scans = 0;  // older than the last processed one
  int64_t stale_odometry = 0;
  int64_t scans_without_objects = 0;
  int64_t scans_without_odometry = 0;
  int64_t resets = 0;  // time went backwards
};

struct NodeOutput {
  UpdateResult result;
  std::vector<Particle> particles;
};

class LocalizerNode {
 public:
  LocalizerNode(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount);

  void on_odometry(int64_t utime, const Pose2& pose);
  void on_initial_pose(const Pose2& pose, const std::vector<double>& sigma);
  void on_scan(const LaserScan& scan);
  void on_objects(const LineObjectSet& objects);
  // Processes the waiting scan if its objects are in, or if `wait_us` has
  // passed since the scan's utime (host time of its measurement) by
  // `now_utime`; INT64_MAX flushes it, a very small value never waits it out.
  std::optional<NodeOutput> poll(int64_t now_utime, int64_t wait_us);

  const NodeCounters& counters() const { return counters_; }
  std::size_t map_memory_bytes() const { return filter_.map_memory_bytes(); }
  bool needs_objects() const { return options_.mode != LocalizerMode::kLfm; }

 private:
  NodeOutput process(const LaserScan& scan, const LineObjectSet* objects);
  std::optional<Pose2> odometry_at(int64_t utime) const;
  void reset();

  LocalizerOptions options_;
  ParticleFilter filter_;
  Pose2 start_pose_;
  std::vector<double> start_sigma_;
  std::deque<std::pair<int64_t, Pose2>> odometry_;
  std::optional<Pose2> last_odometry_used_;
  int64_t last_scan_utime_ = -1;
  std::optional<LaserScan> waiting_;
  int64_t waiting_since_ = 0;
  std::optional<LineObjectSet> waiting_objects_;
  NodeCounters counters_;
};

}  // namespace slamer

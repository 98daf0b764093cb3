#include "localizer/localizer_node.hpp"

#include <limits>

namespace slamer {
namespace {

constexpr int64_t kBackwardsReset = 1'000'000;  // [us] a jump back this large is a new run, not jitter
constexpr std::size_t kOdometryKept = 2000;     // 20 s at 100 Hz

}  // namespace

LocalizerNode::LocalizerNode(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount)
    : options_(options),
      filter_(map, options, lidar_mount),
      start_pose_(options.initial_pose),
      start_sigma_(options.initial_sigma) {
  filter_.initialize(start_pose_, start_sigma_);
}

void LocalizerNode::reset() {
  ++counters_.resets;
  odometry_.clear();
  last_odometry_used_.reset();
  last_scan_utime_ = -1;
  waiting_.reset();
  waiting_objects_.reset();
  filter_.initialize(start_pose_, start_sigma_);
}

void LocalizerNode::on_odometry(int64_t utime, const Pose2& pose) {
  if (!odometry_.empty() && utime <= odometry_.back().first) {
    if (odometry_.back().first - utime > kBackwardsReset) {
      reset();
    } else {
      ++counters_.stale_odometry;
      return;
    }
  }
  odometry_.emplace_back(utime, pose);
  while (odometry_.size() > kOdometryKept) {
    odometry_.pop_front();
  }
}

void LocalizerNode::on_initial_pose(const Pose2& pose, const std::vector<double>& sigma) {
  start_pose_ = pose;
  start_sigma_ = sigma;
  filter_.initialize(pose, sigma);
  last_odometry_used_.reset();  // the next scan's odometry is the new reference
}

void LocalizerNode::on_scan(const LaserScan& scan) {
  if (last_scan_utime_ >= 0 && scan.utime <= last_scan_utime_) {
    if (last_scan_utime_ - scan.utime > kBackwardsReset) {
      reset();
    } else {
      ++counters_.stale_scans;
      return;
    }
  }
  waiting_ = scan;
  waiting_since_ = scan.utime;
  if (waiting_objects_ && waiting_objects_->utime != scan.utime) {
    waiting_objects_.reset();
  }
}

void LocalizerNode::on_objects(const LineObjectSet& objects) {
  waiting_objects_ = objects;  // matched to its scan by utime in poll()
}

std::optional<Pose2> LocalizerNode::odometry_at(int64_t utime) const {
  if (odometry_.empty()) {
    return std::nullopt;
  }
  if (utime >= odometry_.back().first) {
    return odometry_.back().second;  // not there yet: the latest is the best guess
  }
  for (std::size_t i = odometry_.size() - 1; i > 0; --i) {
    if (odometry_[i - 1].first <= utime) {
      const auto& [t0, p0] = odometry_[i - 1];
      const auto& [t1, p1] = odometry_[i];
      return interpolate(p0, p1, static_cast<double>(utime - t0) / static_cast<double>(t1 - t0));
    }
  }
  return odometry_.front().second;
}

std::optional<NodeOutput> LocalizerNode::poll(int64_t now_utime, int64_t wait_us) {
  if (!waiting_) {
    return std::nullopt;
  }
  const bool have_objects = waiting_objects_ && waiting_objects_->utime == waiting_->utime;
  const bool waited = now_utime == std::numeric_limits<int64_t>::max() || now_utime - waiting_since_ >= wait_us;
  if (needs_objects() && !have_objects && !waited) {
    return std::nullopt;
  }
  if (needs_objects() && !have_objects) {
    ++counters_.scans_without_objects;
  }
  const LaserScan scan = std::move(*waiting_);
  waiting_.reset();
  const std::optional<LineObjectSet> objects = have_objects ? waiting_objects_ : std::nullopt;
  waiting_objects_.reset();
  return process(scan, objects ? &*objects : nullptr);
}

NodeOutput LocalizerNode::process(const LaserScan& scan, const LineObjectSet* objects) {
  const std::optional<Pose2> odometry = odometry_at(scan.utime);
  if (!odometry) {
    ++counters_.scans_without_odometry;
  } else {
    if (last_odometry_used_) {
      filter_.predict(*last_odometry_used_, *odometry);
    }
    last_odometry_used_ = odometry;
  }
  last_scan_utime_ = scan.utime;
  NodeOutput output;
  output.result = filter_.update(scan, objects);
  output.particles = filter_.particles();
  return output;
}

}  // namespace slamer

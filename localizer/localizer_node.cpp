#include "localizer/localizer_node.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "localizer/class_map_check.hpp"

namespace slamer {
namespace {

constexpr std::size_t kOdometryKept = 2000;  // 20 s at 100 Hz
// A bound on memory only (about 9 kB a scan): how long a scan waits is
// objects_wait, in time. A count (it was 16, 0.4 s at 40 Hz) cut the wait short
// whenever the recognizer lagged more scans than that, however long objects_wait.
constexpr std::size_t kMaxWaiting = 1024;
// Scans remembered after they went, to tell objects that came late (a drop of
// ours) from objects of a scan we never had: 10 s at 40 Hz, far beyond any wait.
constexpr std::size_t kProcessedKept = 400;
// Objects held for a scan that has not come yet: 1.6 s at 40 Hz. Reordering
// between two senders is milliseconds; more is a scan lost on the way here.
constexpr std::size_t kEarlyKept = 64;
// Nor objects further ahead of the newest scan than this: not of a scan on its
// way (a recognizer's clock gone wrong), and held they would cut every wait short.
constexpr int64_t kEarlyReach = 1'000'000;  // [us]

double seconds(int64_t microseconds) {
  return static_cast<double>(microseconds) * 1e-6;
}
int64_t microseconds(double s) {
  return static_cast<int64_t>(s * 1e6);
}

}  // namespace

LocalizerNode::LocalizerNode(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount)
    : options_((check_class_map(options, map), options)),  // before the map's fields are built
      filter_(map, options, lidar_mount),
      start_pose_(options.initial_pose),
      start_sigma_(options.initial_sigma) {
  filter_.initialize(start_pose_, start_sigma_);
}

void LocalizerNode::reset() {
  ++counters_.resets;
  scan_order_.reset();
  odometry_order_.reset();
  odometry_.clear();
  last_odometry_used_.reset();
  last_processed_utime_.reset();
  last_objects_utime_.reset();
  first_scan_utime_.reset();
  pending_.clear();
  processed_utimes_.clear();
  early_objects_.clear();
  health_ = {};
  filter_.initialize(start_pose_, start_sigma_);
}

void LocalizerNode::on_odometry(int64_t utime, const Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    ++counters_.invalid_odometry;  // one NaN would carry into every particle
    return;
  }
  switch (odometry_order_.check(utime)) {
    case Arrival::kStale:
      ++counters_.stale_odometry;
      return;
    case Arrival::kRestart:
      reset();
      odometry_order_.check(utime);
      break;
    case Arrival::kInOrder:
      break;
  }
  odometry_.emplace_back(utime, pose);
  while (odometry_.size() > kOdometryKept) {
    odometry_.pop_front();
  }
}

namespace {
bool valid_pose_and_sigma(const Pose2& pose, const std::vector<double>& sigma) {
  const auto finite = [](double v) { return std::isfinite(v); };
  return finite(pose.x) && finite(pose.y) && finite(pose.theta) && sigma.size() == 3 &&
         std::all_of(sigma.begin(), sigma.end(), [](double v) { return std::isfinite(v) && v >= 0.0; });
}
}  // namespace

bool LocalizerNode::on_initial_pose(const Pose2& pose, const std::vector<double>& sigma) {
  if (!valid_pose_and_sigma(pose, sigma)) {
    ++counters_.invalid_initial_poses;
    return false;
  }
  resume_.reset();
  start_pose_ = pose;
  start_sigma_ = sigma;
  filter_.initialize(pose, sigma);
  last_odometry_used_.reset();  // the next scan's odometry is the new reference
  return true;
}

bool LocalizerNode::resume(const Pose2& pose, const std::vector<double>& sigma, int64_t saved_utime) {
  if (!valid_pose_and_sigma(pose, sigma)) {
    ++counters_.invalid_initial_poses;
    return false;
  }
  resume_ = Resume{pose, sigma, saved_utime};
  return true;
}

void LocalizerNode::start_resumed(int64_t scan_utime) {
  const Resume r = *resume_;
  resume_.reset();
  const double downtime = seconds(scan_utime - r.saved_utime);
  // A second of clock disagreement is tolerated: the file is written from the scans' own times.
  resumed_ = Resumed{downtime, downtime < -1.0 || downtime > options_.resume.max_downtime};
  last_odometry_used_.reset();
  if (resumed_->global) {
    filter_.initialize_global();
    return;
  }
  const double dt = std::max(downtime, 0.0);
  const double moved = options_.resume.speed * dt;
  const double turned = options_.resume.turn_rate * dt;
  const std::vector<double> grown{std::hypot(r.sigma[0], moved), std::hypot(r.sigma[1], moved),
                                  std::min(std::hypot(r.sigma[2], turned), std::numbers::pi)};
  start_pose_ = r.pose;  // a restart of the stream starts here again, confirmed anew
  start_sigma_ = grown;
  filter_.initialize(r.pose, r.sigma, grown, options_.resume.moved_fraction);
  filter_.require_confirmation();
}

void LocalizerNode::restart_odometry() {
  odometry_.clear();
  last_odometry_used_.reset();
}

void LocalizerNode::request_global_localization() {
  resume_.reset();
  filter_.initialize_global();
}

void LocalizerNode::on_scan(const LaserScan& scan, int64_t arrival_utime) {
  last_scan_arrival_ = arrival_utime;
  switch (scan_order_.check(scan.utime)) {
    case Arrival::kStale:
      ++counters_.stale_scans;
      return;
    case Arrival::kRestart:
      reset();
      scan_order_.check(scan.utime);
      break;
    case Arrival::kInOrder:
      break;
  }
  if (!first_scan_utime_) {
    first_scan_utime_ = scan.utime;
  }
  pending_.push_back({scan, arrival_utime, take_early(scan.utime)});
}

void LocalizerNode::hold_early(const LineObjectSet& objects) {
  const auto later = std::find_if(early_objects_.begin(), early_objects_.end(),
                                  [&](const LineObjectSet& held) { return held.utime >= objects.utime; });
  if (later != early_objects_.end() && later->utime == objects.utime) {
    ++counters_.stale_objects;  // twice
    return;
  }
  early_objects_.insert(later, objects);
  if (early_objects_.size() > kEarlyKept) {
    early_objects_.pop_front();
    ++counters_.objects_without_scan;
  }
}

std::optional<LineObjectSet> LocalizerNode::take_early(int64_t scan_utime) {
  // Held objects of scans before this one: those scans would be stale now.
  while (!early_objects_.empty() && early_objects_.front().utime < scan_utime) {
    early_objects_.pop_front();
    ++counters_.objects_without_scan;
  }
  // Held before the first scan, and too far ahead of it.
  while (!early_objects_.empty() && early_objects_.back().utime - scan_utime > kEarlyReach) {
    early_objects_.pop_back();
    ++counters_.objects_without_scan;
  }
  if (early_objects_.empty() || early_objects_.front().utime != scan_utime) {
    return std::nullopt;
  }
  std::optional<LineObjectSet> objects = std::move(early_objects_.front());
  early_objects_.pop_front();
  ++counters_.objects_before_scan;
  return objects;
}

void LocalizerNode::on_objects(const LineObjectSet& objects) {
  if (!needs_objects()) {
    return;  // LFM: scans go without waiting, so objects have nothing to join
  }
  if (!last_objects_utime_ || objects.utime > *last_objects_utime_) {
    last_objects_utime_ = objects.utime;
  }
  const auto waiting =
      std::find_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.scan.utime == objects.utime; });
  if (waiting != pending_.end() && waiting->objects) {
    ++counters_.stale_objects;  // twice
    return;
  }
  if (waiting == pending_.end()) {
    const std::optional<int64_t>& newest_scan = scan_order_.last();
    if (!newest_scan || (objects.utime > *newest_scan && objects.utime - *newest_scan <= kEarlyReach)) {
      hold_early(objects);  // its scan may still come
      return;
    }
    const bool had_scan =
        std::find(processed_utimes_.begin(), processed_utimes_.end(), objects.utime) != processed_utimes_.end();
    ++(had_scan ? counters_.stale_objects : counters_.objects_without_scan);
    return;
  }
  waiting->objects = objects;
}

bool LocalizerNode::objects_missing(int64_t scan_utime) const {
  if (!needs_objects()) {
    return false;
  }
  const std::optional<int64_t>& since = last_objects_utime_ ? last_objects_utime_ : first_scan_utime_;
  return since && scan_utime - *since > microseconds(options_.inputs.objects_timeout);
}

std::optional<UpdateResult> LocalizerNode::poll(int64_t now_utime) {
  const bool flush = now_utime == std::numeric_limits<int64_t>::max();
  if (pending_.empty()) {
    if (flush) {  // the end: the scans of held objects will not come
      counters_.objects_without_scan += static_cast<int64_t>(early_objects_.size());
      early_objects_.clear();
    }
    return std::nullopt;
  }
  const Pending& oldest = pending_.front();
  // The oldest scan stops waiting (for odometry or objects) at the end of the
  // input, when too many are held, or once it has waited `wait` seconds.
  const auto waited = [&](double wait) {
    return flush || pending_.size() > kMaxWaiting || now_utime - oldest.arrival_utime >= microseconds(wait);
  };
  // The odometry is interpolated to the scan's time: a scan that came before
  // the odometry past its time (a stalled host delivers both in a burst) waits
  // for it, up to odometry_wait, unless the odometry is missing. Otherwise the
  // scan's prediction depended on which datagram this process read first, and
  // a replay (the recognizer's objects logged right after their scan) did not
  // repeat the live run.
  const bool odometry_ready =
      odometry_.empty() || odometry_.back().first >= oldest.scan.utime ||
      oldest.scan.utime - odometry_.back().first > microseconds(options_.inputs.odometry_timeout) ||
      waited(options_.inputs.odometry_wait);
  if (!odometry_ready) {
    return std::nullopt;
  }
  const bool release =
      !needs_objects() || oldest.objects || waited(options_.inputs.objects_wait) ||
      objects_missing(pending_.back().scan.utime) ||
      // The recognizer works in order: a later scan's objects mean these will not come.
      std::any_of(pending_.begin() + 1, pending_.end(), [](const Pending& p) { return p.objects.has_value(); }) ||
      !early_objects_.empty();  // held ones are of later scans
  if (!release) {
    return std::nullopt;
  }
  const Pending next = std::move(pending_.front());
  pending_.pop_front();
  return process(next);
}

bool LocalizerNode::scans_missing(int64_t now_utime, int64_t since_utime) const {
  return now_utime - last_scan_arrival_.value_or(since_utime) > microseconds(options_.inputs.scan_timeout);
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

UpdateResult LocalizerNode::process(const Pending& pending) {
  const int64_t utime = pending.scan.utime;
  processed_utimes_.push_back(utime);
  if (processed_utimes_.size() > kProcessedKept) {
    processed_utimes_.pop_front();
  }
  if (resume_) {
    start_resumed(utime);
  }
  constexpr double kNever = std::numeric_limits<double>::infinity();
  health_.odometry_age = odometry_.empty() ? kNever : std::max(0.0, seconds(utime - odometry_.back().first));
  health_.odometry_missing = health_.odometry_age > options_.inputs.odometry_timeout;
  health_.objects_age = last_objects_utime_ ? std::max(0.0, seconds(utime - *last_objects_utime_)) : kNever;
  health_.objects_missing = objects_missing(utime);
  if (needs_objects() && !pending.objects) {
    ++counters_.scans_without_objects;
  }
  if (health_.odometry_missing) {
    // Without odometry the robot may have moved anywhere its speed allows; when
    // odometry comes back its increment starts from there, not from before the gap.
    ++counters_.scans_without_odometry;
    if (last_processed_utime_) {
      filter_.diffuse(seconds(utime - *last_processed_utime_));
    }
    last_odometry_used_.reset();
  } else {
    const std::optional<Pose2> odometry = odometry_at(utime);
    if (last_odometry_used_) {
      // last_odometry_used_ was taken at the last processed scan's time (the
      // two are set and reset together); the motion model takes a negative time as 0.
      filter_.predict(*last_odometry_used_, *odometry, seconds(utime - *last_processed_utime_));
    }
    last_odometry_used_ = odometry;
  }
  last_processed_utime_ = utime;
  return filter_.update(pending.scan, pending.objects ? &*pending.objects : nullptr);
}

}  // namespace slamer

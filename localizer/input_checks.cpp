#include "localizer/input_checks.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slamer {
namespace {

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

}  // namespace

bool StreamTime::near(int64_t a, int64_t b) const {
  const double step = static_cast<double>(b - a) * 1e-6;
  // Until the stream's pace is known (its second message), a minute ahead is plausible.
  const double ahead = mean_interval_ == 0.0 ? 60.0 : std::max(limits_.time_ahead, 10.0 * mean_interval_);
  return step <= ahead && step >= -limits_.time_back;
}

void StreamTime::accept(int64_t utime) {
  if (last_ && utime > *last_) {
    const double interval = static_cast<double>(utime - *last_) * 1e-6;
    mean_interval_ = mean_interval_ == 0.0 ? interval : 0.9 * mean_interval_ + 0.1 * interval;
  }
  last_ = utime;
  candidate_.reset();
  agreeing_ = 0;
}

TimeVerdict StreamTime::check(int64_t utime) {
  if (!last_ || near(*last_, utime)) {
    accept(utime);
    return TimeVerdict::kAccept;
  }
  // Far from the stream: the start of a move only if the next ones agree.
  if (candidate_ && near(*candidate_, utime)) {
    ++agreeing_;
  } else {
    agreeing_ = 1;
  }
  candidate_ = utime;
  if (agreeing_ >= limits_.confirm) {
    mean_interval_ = 0.0;  // a new stretch of the stream: its pace is learned again
    accept(utime);
    return TimeVerdict::kMoved;
  }
  return TimeVerdict::kRefuse;
}

std::string scan_problem(const LaserScan& scan, const InputLimits& limits) {
  if (scan.utime <= 0) {
    return "utime " + std::to_string(scan.utime) + " is no time";
  }
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment) || scan.angle_increment == 0.0 ||
      std::abs(scan.angle_increment) * static_cast<double>(scan.ranges.size()) > 2.0 * M_PI + 1e-6) {
    return "impossible angles (angle_min " + format("%g", scan.angle_min) + ", increment " +
           format("%g", scan.angle_increment) + ")";
  }
  if (!std::isfinite(scan.range_max) || !(scan.range_max > 0.0f) || !std::isfinite(scan.range_min) ||
      scan.range_min < 0.0f || scan.range_min >= scan.range_max) {
    return "impossible range limits";
  }
  if (scan.ranges.size() < 3 || static_cast<int>(scan.ranges.size()) > limits.max_beams) {
    return std::to_string(scan.ranges.size()) + " beams (the sensor has " + std::to_string(limits.max_beams) + ")";
  }
  // Not one measured range: nothing to weigh the particles with, and a scan
  // stamped newer than a real one in flight would make that one stale.
  if (std::none_of(scan.ranges.begin(), scan.ranges.end(),
                   [&](float r) { return r >= scan.range_min && r <= scan.range_max; })) {
    return "no range within [range_min, range_max] in " + std::to_string(scan.ranges.size()) + " beams";
  }
  return "";
}

std::string StreamRestart::check(int64_t seq, int64_t utime) {
  std::string restart;
  if (seq_ && utime_ && seq < *seq_ && utime > *utime_) {
    restart = "seq " + std::to_string(*seq_) + " -> " + std::to_string(seq) +
              format(" after %.2f s", static_cast<double>(utime - *utime_) * 1e-6);
  }
  if (!utime_ || utime > *utime_) {
    seq_ = seq;
    utime_ = utime;
  }
  return restart;
}

std::string odometry_step_problem(const Pose2& from, int64_t from_utime, const Pose2& to, int64_t to_utime,
                                  const InputLimits& limits) {
  if (!std::isfinite(to.x) || !std::isfinite(to.y) || !std::isfinite(to.theta)) {
    return "not a finite pose";
  }
  if (to_utime <= 0) {
    return "utime " + std::to_string(to_utime) + " is no time";
  }
  const double dt = static_cast<double>(to_utime - from_utime) * 1e-6;
  if (dt <= 0.0) {
    return "";
  }
  const double distance = std::hypot(to.x - from.x, to.y - from.y);
  const double turn = std::abs(wrap_angle(to.theta - from.theta));
  if (distance > limits.max_speed * dt + limits.odometry_margin ||
      turn > limits.max_yaw_rate * dt + limits.odometry_margin) {
    return format("a jump of %.2f m", distance) + format(" and %.2f rad in %.3f s", turn, dt);
  }
  return "";
}

std::string initial_pose_problem(const Pose2& pose, const std::array<double, 9>& covariance, bool on_map) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    return "not a finite pose";
  }
  for (const double c : covariance) {
    if (!std::isfinite(c)) {
      return "a covariance that is not finite";
    }
  }
  const Eigen::Matrix3d c = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(covariance.data());
  if ((c - c.transpose()).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, c.cwiseAbs().maxCoeff())) {
    return "a covariance that is not symmetric";
  }
  const Eigen::Vector3d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues();
  if (eigenvalues.minCoeff() < -1e-12 * std::max(1.0, eigenvalues.cwiseAbs().maxCoeff())) {
    return "a covariance that is not positive semi-definite";
  }
  if (!on_map) {
    return format("a position (%.2f, %.2f) off the map", pose.x, pose.y);
  }
  return "";
}

void RefusalCounter::count(const std::string& channel, const std::string& reason) {
  Reasons& r = channels_[channel];
  ++r.total;
  ++r.unreported;
  r.last_reason = reason;
}

int64_t RefusalCounter::total(const std::string& channel) const {
  const auto it = channels_.find(channel);
  return it == channels_.end() ? 0 : it->second.total;
}

std::string RefusalCounter::take_summary() {
  std::string summary;
  for (auto& [channel, r] : channels_) {
    if (r.unreported > 0) {
      summary += (summary.empty() ? "" : ", ") + channel + " " + std::to_string(r.unreported) +
                 " (last: " + r.last_reason + ")";
      r.unreported = 0;
    }
  }
  return summary.empty() ? "" : "refused " + summary;
}

}  // namespace slamer

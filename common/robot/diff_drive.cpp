#include "common/robot/diff_drive.hpp"

#include <numbers>

namespace slamer {

BodyMotion motion_from_wheels(const DiffDriveOptions& base, double left_travel, double right_travel) {
  return {(left_travel + right_travel) / 2.0, (right_travel - left_travel) / base.tread};
}

double wheel_travel(double ticks, double wheel_radius, const DiffDriveOptions& base) {
  return 2.0 * std::numbers::pi * wheel_radius * ticks / base.ticks_per_wheel_rev();
}

double travel_ticks(double travel, double wheel_radius, const DiffDriveOptions& base) {
  return travel * base.ticks_per_wheel_rev() / (2.0 * std::numbers::pi * wheel_radius);
}

bool DiffDriveOdometry::update(int64_t utime, int64_t left_ticks, int64_t right_ticks) {
  if (!last_utime_) {
    last_utime_ = utime;
    last_left_ = left_ticks;
    last_right_ = right_ticks;
    return true;
  }
  if (utime <= *last_utime_) {
    return false;
  }
  const double left = wheel_travel(static_cast<double>(left_ticks - last_left_), base_.wheel_radius_left, base_);
  const double right = wheel_travel(static_cast<double>(right_ticks - last_right_), base_.wheel_radius_right, base_);
  const BodyMotion motion = motion_from_wheels(base_, left, right);
  pose_ = compose(pose_, exp_se2({motion.distance, 0.0, motion.rotation}));
  const double dt = static_cast<double>(utime - *last_utime_) * 1e-6;
  speed_ = motion.distance / dt;
  yaw_rate_ = motion.rotation / dt;
  last_utime_ = utime;
  last_left_ = left_ticks;
  last_right_ = right_ticks;
  return true;
}

void DiffDriveOdometry::reset(const Pose2& pose) {
  pose_ = pose;
  speed_ = 0.0;
  yaw_rate_ = 0.0;
  last_utime_.reset();
}

}  // namespace slamer

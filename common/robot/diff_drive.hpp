// Differential-drive kinematics and wheel odometry.
//
// Wheel travel from encoder ticks: d = 2 pi r * ticks / (counts_per_rev * gear).
// Between two encoder readings the base is taken to move on a circular arc
// (constant v and omega): ds = (dr + dl) / 2, dtheta = (dr - dl) / tread,
// integrated exactly with the SE(2) exponential, not the Euler step.
#pragma once

#include <cstdint>
#include <optional>

#include "common/geometry/se2.hpp"
#include "common/robot/robot_options.hpp"

namespace slamer {

struct BodyMotion {
  double distance = 0.0;  // forward travel [m]
  double rotation = 0.0;  // heading change [rad]
};

BodyMotion motion_from_wheels(const DiffDriveOptions& base, double left_travel, double right_travel);
// Wheel travel [m] from a tick difference.
double wheel_travel(double ticks, double wheel_radius, const DiffDriveOptions& base);
// Ticks of wheel travel (fractional; the caller accumulates and rounds).
double travel_ticks(double travel, double wheel_radius, const DiffDriveOptions& base);

// Integrates cumulative encoder counts into a pose in the odometry frame.
class DiffDriveOdometry {
 public:
  explicit DiffDriveOdometry(const DiffDriveOptions& base) : base_(base) {}

  // Feeds cumulative ticks measured at `utime`. Returns false (and ignores the
  // reading) when time does not move forward; the first reading only anchors.
  bool update(int64_t utime, int64_t left_ticks, int64_t right_ticks);
  void reset(const Pose2& pose = {});

  const Pose2& pose() const { return pose_; }
  double speed() const { return speed_; }        // [m/s] over the last update
  double yaw_rate() const { return yaw_rate_; }  // [rad/s]
  std::optional<int64_t> last_utime() const { return last_utime_; }

 private:
  DiffDriveOptions base_;
  Pose2 pose_;
  double speed_ = 0.0;
  double yaw_rate_ = 0.0;
  std::optional<int64_t> last_utime_;
  int64_t last_left_ = 0;
  int64_t last_right_ = 0;
};

}  // namespace slamer

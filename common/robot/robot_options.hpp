// The robot's fixed description: differential-drive base (wheels, encoders,
// limits) and the LiDAR (model and mount on the base). One file per robot in
// config/robots/, shared by the simulator, the wheel driver and the localizer.
#pragma once

#include <string>

#include "common/config/config_reader.hpp"
#include "common/geometry/se2.hpp"

namespace slamer {

struct DiffDriveOptions {
  double wheel_radius_left = 0.07455;   // [m]
  double wheel_radius_right = 0.07455;  // [m]
  double tread = 0.30737;               // [m] distance between the wheels
  int counts_per_motor_rev = 400;       // encoder counts per motor revolution
  double gear_ratio = 75.0;             // motor revolutions per wheel revolution
  double max_speed = 0.9;               // [m/s]
  double max_yaw_rate = 3.14;           // [rad/s]
  double max_accel = 1.5;               // [m/s^2]
  double max_yaw_accel = 6.28;          // [rad/s^2]

  double ticks_per_wheel_rev() const { return counts_per_motor_rev * gear_ratio; }
};

struct LidarOptions {
  std::string frame = "laser";
  Pose2 mount{0.0, 0.0, 0.0};       // sensor pose on the base
  double angle_min = -2.35619449;   // [rad] first beam (-135 deg)
  double angle_max = 2.35619449;    // [rad] last beam (+135 deg)
  int beams = 1081;                 // 0.25 deg steps
  double scan_period = 0.025;       // [s] (40 Hz)
  int steps_per_revolution = 1440;  // beam slots in a full turn: time_increment = scan_period / this
  double range_min = 0.06;          // [m]
  double range_max = 30.0;          // [m]

  double angle_increment() const { return beams > 1 ? (angle_max - angle_min) / (beams - 1) : 0.0; }
  double time_increment() const { return scan_period / steps_per_revolution; }
};

struct RobotOptions {
  std::string name = "icart_mini";
  DiffDriveOptions base;
  LidarOptions lidar;
};

void read_options(const ConfigReader& reader, DiffDriveOptions* options);
void read_options(const ConfigReader& reader, LidarOptions* options);
void read_options(const ConfigReader& reader, RobotOptions* options);
// A pose written as [x, y, theta].
Pose2 read_pose(const ConfigReader& reader, std::string_view key, const Pose2& fallback);

}  // namespace slamer

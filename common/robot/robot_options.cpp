#include "common/robot/robot_options.hpp"

#include <cmath>

namespace slamer {

Pose2 read_pose(const ConfigReader& reader, std::string_view key, const Pose2& fallback) {
  std::vector<double> values{fallback.x, fallback.y, fallback.theta};
  reader.read(key, &values, {}, 3);
  return {values[0], values[1], wrap_angle(values[2])};
}

void read_options(const ConfigReader& reader, DiffDriveOptions* o) {
  reader.read("wheel_radius_left", &o->wheel_radius_left, positive());
  reader.read("wheel_radius_right", &o->wheel_radius_right, positive());
  reader.read("tread", &o->tread, positive());
  reader.read("counts_per_motor_rev", &o->counts_per_motor_rev, at_least(1));
  reader.read("gear_ratio", &o->gear_ratio, positive());
  reader.read("max_speed", &o->max_speed, positive());
  reader.read("max_yaw_rate", &o->max_yaw_rate, positive());
  reader.read("max_accel", &o->max_accel, positive());
  reader.read("max_yaw_accel", &o->max_yaw_accel, positive());
}

void read_options(const ConfigReader& reader, LidarOptions* o) {
  reader.read("frame", &o->frame);
  o->mount = read_pose(reader, "mount", o->mount);
  reader.read("angle_min", &o->angle_min, in_range(-M_PI, M_PI));
  reader.read("angle_max", &o->angle_max, in_range(-M_PI, M_PI));
  reader.read("beams", &o->beams, in_range(1, 100000));
  reader.read("scan_period", &o->scan_period, positive());
  reader.read("steps_per_revolution", &o->steps_per_revolution, at_least(1));
  reader.read("range_min", &o->range_min, non_negative());
  reader.read("range_max", &o->range_max, positive());
  if (o->angle_max < o->angle_min) {
    reader.fail("angle_max", "must not be below angle_min");
  }
  if (o->range_max <= o->range_min) {
    reader.fail("range_max", "must exceed range_min");
  }
  if (o->steps_per_revolution < o->beams) {
    reader.fail("steps_per_revolution", "must be at least the number of beams");
  }
}

void read_options(const ConfigReader& reader, RobotOptions* o) {
  reader.read("name", &o->name);
  read_options(reader.section("base"), &o->base);
  read_options(reader.section("lidar"), &o->lidar);
}

}  // namespace slamer

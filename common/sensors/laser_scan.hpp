// A 2D LiDAR scan as the libraries see it (the LCM laser_scan_t without LCM).
// Ranges follow REP 117: +inf = no return within range_max, -inf = closer
// than range_min, NaN = the device reported an error for that beam.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace slamer {

struct LaserScan {
  int64_t utime = 0;         // host time of the first beam [us since the Unix epoch]
  int64_t sensor_utime = 0;  // device clock of the first beam [us]
  int64_t seq = 0;
  std::string frame = "laser";
  double angle_min = 0.0;        // [rad]
  double angle_increment = 0.0;  // [rad]
  float range_min = 0.0f;        // [m]
  float range_max = 0.0f;        // [m]
  float time_increment = 0.0f;   // [s] between beams
  float scan_period = 0.0f;      // [s] between scans
  std::vector<float> ranges;
  std::vector<float> intensities;  // empty or ranges.size()

  double angle(std::size_t beam) const { return angle_min + angle_increment * static_cast<double>(beam); }
  // Time of a beam relative to utime [s].
  double beam_time(std::size_t beam) const { return time_increment * static_cast<double>(beam); }
};

}  // namespace slamer

// The pose a live localizer keeps on disk so a restart (after a clean stop, a
// crash or a power cut) resumes where the robot was: a small YAML file,
//   utime: 1700000000000000   # [us] host time of the scan it is from
//   pose: [x, y, theta]       # [m, m, rad] in the map frame
//   sigma: [sx, sy, stheta]   # [m, m, rad] its standard deviations
// read by the strict config reader (unknown keys, bad numbers: one line).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/geometry/se2.hpp"

namespace slamer {

struct SavedPose {
  int64_t utime = 0;
  Pose2 pose;
  std::vector<double> sigma{0.2, 0.2, 0.1};
};
void read_options(const ConfigReader& reader, SavedPose* saved);
std::string format_saved_pose(const SavedPose& saved);

// Standard deviations (x, y, theta) of a row-major 3x3 covariance, floored so
// that a zero covariance still spreads particles a little.
std::vector<double> sigma_of_covariance(const double covariance[9]);

}  // namespace slamer

#include "localizer/saved_pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/robot/robot_options.hpp"  // read_pose

namespace slamer {

void read_options(const ConfigReader& reader, SavedPose* saved) {
  reader.read("utime", &saved->utime, at_least(0));
  saved->pose = read_pose(reader, "pose", saved->pose);
  reader.read("sigma", &saved->sigma, in_range(0.0, 1000.0), 3);
}

std::string format_saved_pose(const SavedPose& saved) {
  char text[256];
  // %.17g: the file gives back exactly the pose that was written.
  std::snprintf(text, sizeof text, "utime: %lld\npose: [%.17g, %.17g, %.17g]\nsigma: [%.17g, %.17g, %.17g]\n",
                static_cast<long long>(saved.utime), saved.pose.x, saved.pose.y, saved.pose.theta, saved.sigma[0],
                saved.sigma[1], saved.sigma[2]);
  return text;
}

std::vector<double> sigma_of_covariance(const double covariance[9]) {
  return {std::sqrt(std::max(covariance[0], 1e-6)), std::sqrt(std::max(covariance[4], 1e-6)),
          std::sqrt(std::max(covariance[8], 1e-6))};
}

}  // namespace slamer

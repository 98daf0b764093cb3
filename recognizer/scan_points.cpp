#include "recognizer/scan_points.hpp"

#include <cmath>

namespace slamer {

PreparedScan prepare_scan(const LaserScan& scan) {
  PreparedScan prepared;
  const std::size_t n = scan.ranges.size();
  prepared.state.resize(n, BeamState::kUnknown);
  prepared.point.resize(n, Eigen::Vector2d::Zero());
  const bool limits_ok = std::isfinite(scan.range_max) && scan.range_max > 0.0f && std::isfinite(scan.angle_min) &&
                         std::isfinite(scan.angle_increment);
  if (!limits_ok) {
    return prepared;  // a scan without usable geometry tells nothing
  }
  const float range_min = std::isfinite(scan.range_min) ? scan.range_min : 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const float r = scan.ranges[i];
    if (std::isnan(r)) {
      continue;
    }
    if (r > scan.range_max) {  // includes +inf
      prepared.state[i] = BeamState::kNoReturn;
    } else if (r < range_min) {  // includes -inf
      prepared.state[i] = BeamState::kBlocked;
    } else {
      const double a = scan.angle(i);
      prepared.state[i] = BeamState::kHit;
      prepared.point[i] = {r * std::cos(a), r * std::sin(a)};
      prepared.hits.push_back(static_cast<int>(i));
    }
  }
  return prepared;
}

}  // namespace slamer

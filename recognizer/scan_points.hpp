// The beams of a scan as the recognizer uses them: valid returns as points in
// the sensor frame, and per beam whether it returned, passed (no return in
// range), or tells nothing (NaN errors). NaN, -inf and out-of-range values
// never become coordinates or pixel indices.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "common/sensors/laser_scan.hpp"

namespace slamer {

enum class BeamState : uint8_t {
  kHit,       // a return within [range_min, range_max]
  kNoReturn,  // +inf or beyond range_max: the beam went through
  kBlocked,   // -inf or below range_min: something right in front of the sensor
  kUnknown,   // NaN: the device reported an error
};

struct PreparedScan {
  std::vector<BeamState> state;        // per beam
  std::vector<Eigen::Vector2d> point;  // per beam; meaningful for kHit only
  std::vector<int> hits;               // beam indices of kHit beams, in angle order
};

PreparedScan prepare_scan(const LaserScan& scan);

}  // namespace slamer

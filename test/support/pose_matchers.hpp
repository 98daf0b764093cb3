// PoseNear(expected, position_tol, heading_tol): a gmock matcher for anything
// with x, y, theta (Pose2, pose_estimate_t, ...): the position within
// position_tol [m] and the heading within heading_tol [rad], the heading
// difference wrapped to (-pi, pi].
#pragma once

#include <gmock/gmock.h>

#include <cmath>

#include "common/geometry/se2.hpp"

namespace slamer::test {

MATCHER_P3(PoseNear, expected, position_tol, heading_tol,
           "is within " + ::testing::PrintToString(position_tol) + " m and " + ::testing::PrintToString(heading_tol) +
               " rad of (" + ::testing::PrintToString(expected.x) + ", " + ::testing::PrintToString(expected.y) + ", " +
               ::testing::PrintToString(expected.theta) + ")") {
  const double position_error = std::hypot(arg.x - expected.x, arg.y - expected.y);
  const double heading_error = std::abs(wrap_angle(arg.theta - expected.theta));
  *result_listener << "the pose (" << arg.x << ", " << arg.y << ", " << arg.theta << ") is " << position_error
                   << " m and " << heading_error << " rad off";
  return position_error <= position_tol && heading_error <= heading_tol;
}

}  // namespace slamer::test

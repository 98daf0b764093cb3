// A scripted drive for the emulators: segments of constant (v, omega) for a
// duration, played back as motor count increments through the robot's signed
// radii, with the true pose integrated exactly (constant-curvature arcs).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "drivers/wheels/ypspur_params.hpp"

namespace slamer::tfrog {

struct PathSegment {
  double v = 0.0;         // [m/s]
  double omega = 0.0;     // [rad/s]
  double duration = 0.0;  // [s]
};
// "v,omega,duration;v,omega,duration;..."; throws std::runtime_error naming the bad segment.
std::vector<PathSegment> parse_path(const std::string& spec);

class PathPlayer {
 public:
  PathPlayer(std::vector<PathSegment> segments, const Kinematics& kinematics);
  // Advances dt [s]; returns motor count increments (fractional) over it.
  std::array<double, 2> step(double dt);
  bool done() const { return index_ >= segments_.size(); }
  const Pose2& truth() const { return truth_; }
  double distance() const { return distance_; }

 private:
  std::vector<PathSegment> segments_;
  Kinematics k_;
  std::size_t index_ = 0;
  double in_segment_ = 0.0;
  Pose2 truth_;
  double distance_ = 0.0;
};

}  // namespace slamer::tfrog

// Drives the simulated base along a scripted path: go to a point (turning on
// the spot first when it lies far off the heading), turn to a heading, wait.
// Commands respect the base's speed, yaw-rate and acceleration limits.
#pragma once

#include <vector>

#include "common/robot/robot_options.hpp"
#include "tools/sim/world.hpp"

namespace slamer {

struct VelocityCommand {
  double v = 0.0;      // [m/s]
  double omega = 0.0;  // [rad/s]
};

class PathFollower {
 public:
  PathFollower(std::vector<PathStep> path, const DiffDriveOptions& limits);

  // The command for the next `dt` seconds given the true pose.
  VelocityCommand update(const Pose2& pose, double dt);
  bool done() const { return step_ >= path_.size(); }
  std::size_t current_step() const { return step_; }

 private:
  VelocityCommand desired(const Pose2& pose, double dt);

  std::vector<PathStep> path_;
  DiffDriveOptions limits_;
  std::size_t step_ = 0;
  double waited_ = 0.0;
  VelocityCommand last_;
};

}  // namespace slamer

#include "tools/sim/path_follower.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {
namespace {

constexpr double kReached = 0.05;         // [m] a go_to is done this close
constexpr double kAligned = 0.01;         // [rad] a turn_to is done this close
constexpr double kTurnOnSpotAbove = 0.6;  // [rad] heading error that stops forward motion
constexpr double kHeadingGain = 2.0;      // [1/s]
constexpr double kDistanceGain = 1.0;     // [1/s]

double toward(double current, double target, double max_change) {
  return current + std::clamp(target - current, -max_change, max_change);
}

}  // namespace

PathFollower::PathFollower(std::vector<PathStep> path, const DiffDriveOptions& limits)
    : path_(std::move(path)), limits_(limits) {}

VelocityCommand PathFollower::desired(const Pose2& pose, double dt) {
  while (step_ < path_.size()) {
    const PathStep& step = path_[step_];
    switch (step.kind) {
      case PathStep::Kind::kGoTo: {
        const Eigen::Vector2d to_target = step.target - Eigen::Vector2d(pose.x, pose.y);
        const double distance = to_target.norm();
        if (distance < kReached) {
          ++step_;
          continue;
        }
        const double error = angle_diff(std::atan2(to_target.y(), to_target.x()), pose.theta);
        const double omega = kHeadingGain * error;
        // Slow down to stop at the point and while the heading is far off.
        const double v = std::abs(error) > kTurnOnSpotAbove
                             ? 0.0
                             : std::min(step.speed, kDistanceGain * distance + 0.05) * std::cos(error);
        return {v, omega};
      }
      case PathStep::Kind::kTurnTo: {
        const double error = angle_diff(step.heading, pose.theta);
        if (std::abs(error) < kAligned && std::abs(last_.omega) < 0.05) {
          ++step_;
          continue;
        }
        return {0.0, kHeadingGain * error};
      }
      case PathStep::Kind::kWait:
        if (waited_ >= step.duration) {
          waited_ = 0.0;
          ++step_;
          continue;
        }
        waited_ += dt;
        return {0.0, 0.0};
    }
  }
  return {0.0, 0.0};
}

VelocityCommand PathFollower::update(const Pose2& pose, double dt) {
  VelocityCommand want = desired(pose, dt);
  want.v = std::clamp(want.v, -limits_.max_speed, limits_.max_speed);
  want.omega = std::clamp(want.omega, -limits_.max_yaw_rate, limits_.max_yaw_rate);
  last_.v = toward(last_.v, want.v, limits_.max_accel * dt);
  last_.omega = toward(last_.omega, want.omega, limits_.max_yaw_accel * dt);
  return last_;
}

}  // namespace slamer

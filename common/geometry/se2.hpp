// Planar rigid-body poses (the group SE(2)) and angle helpers.
//
// A Pose2 (x, y, theta) maps points from its child frame into its parent
// frame: p_parent = R(theta) * p_child + (x, y). compose(a, b) is "b expressed
// in a's frame, seen from a's parent" (a * b as 3x3 homogeneous matrices).
// interpolate() follows the group geodesic (exp/log), i.e. the constant-velocity
// arc a differential-drive robot drives between two poses, not a straight line.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

namespace slamer {

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // [rad], kept in (-pi, pi] by every function below
};

// Body-frame velocity integrated over unit time: the tangent space of SE(2).
struct Twist2 {
  double vx = 0.0;
  double vy = 0.0;
  double omega = 0.0;
};

// Maps any finite angle into (-pi, pi]. Non-finite input is returned as NaN.
double wrap_angle(double angle);

// The shortest signed rotation from `from` to `to`, in (-pi, pi].
double angle_diff(double to, double from);

Pose2 compose(const Pose2& a, const Pose2& b);
Pose2 inverse(const Pose2& pose);
// The pose of `to` in the frame of `from`: inverse(from) * to.
Pose2 between(const Pose2& from, const Pose2& to);
Eigen::Vector2d transform_point(const Pose2& pose, const Eigen::Vector2d& point);

Eigen::Matrix3d to_matrix(const Pose2& pose);
Pose2 from_matrix(const Eigen::Matrix3d& matrix);

// Group exponential and logarithm (exact, with series near omega = 0).
Pose2 exp_se2(const Twist2& twist);
Twist2 log_se2(const Pose2& pose);

// Pose at fraction t along the geodesic from a to b (t = 0 -> a, t = 1 -> b;
// t outside [0, 1] extrapolates along the same arc).
Pose2 interpolate(const Pose2& a, const Pose2& b, double t);

// Distance from p to the segment a-b (to the nearer end where p projects outside it).
double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Weighted mean direction atan2(sum w sin, sum w cos). Empty input, mismatched
// sizes, negative or non-finite weights, or a resultant too short to define a
// direction (e.g. two opposite angles) give nullopt. Empty weights = all equal.
std::optional<double> circular_mean(std::span<const double> angles, std::span<const double> weights = {});

}  // namespace slamer

#include "common/geometry/se2.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slamer {
namespace {

// sin(w)/w and (1 - cos(w))/w, with Taylor series where the quotient loses precision.
void arc_coefficients(double w, double* sin_over_w, double* one_minus_cos_over_w) {
  if (std::abs(w) < 1e-5) {
    const double w2 = w * w;
    *sin_over_w = 1.0 - w2 / 6.0;
    *one_minus_cos_over_w = w / 2.0 - w * w2 / 24.0;
  } else {
    *sin_over_w = std::sin(w) / w;
    *one_minus_cos_over_w = (1.0 - std::cos(w)) / w;
  }
}

}  // namespace

double wrap_angle(double angle) {
  if (!std::isfinite(angle)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  constexpr double kPi = std::numbers::pi;
  if (angle > -kPi && angle <= kPi) {
    return angle;
  }
  double wrapped = std::remainder(angle, 2.0 * kPi);  // in [-pi, pi]
  if (wrapped <= -kPi) {
    wrapped += 2.0 * kPi;
  }
  return wrapped;
}

double angle_diff(double to, double from) {
  return wrap_angle(to - from);
}

Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrap_angle(a.theta + b.theta)};
}

Pose2 inverse(const Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  return {-c * pose.x - s * pose.y, s * pose.x - c * pose.y, wrap_angle(-pose.theta)};
}

Pose2 between(const Pose2& from, const Pose2& to) {
  return compose(inverse(from), to);
}

Eigen::Vector2d transform_point(const Pose2& pose, const Eigen::Vector2d& point) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  return {pose.x + c * point.x() - s * point.y(), pose.y + s * point.x() + c * point.y()};
}

Eigen::Matrix3d to_matrix(const Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  Eigen::Matrix3d m;
  m << c, -s, pose.x, s, c, pose.y, 0.0, 0.0, 1.0;
  return m;
}

Pose2 from_matrix(const Eigen::Matrix3d& matrix) {
  return {matrix(0, 2), matrix(1, 2), wrap_angle(std::atan2(matrix(1, 0), matrix(0, 0)))};
}

Pose2 exp_se2(const Twist2& twist) {
  double a = 0.0;
  double b = 0.0;
  arc_coefficients(twist.omega, &a, &b);
  return {a * twist.vx - b * twist.vy, b * twist.vx + a * twist.vy, wrap_angle(twist.omega)};
}

Twist2 log_se2(const Pose2& pose) {
  const double w = wrap_angle(pose.theta);
  double a = 0.0;
  double b = 0.0;
  arc_coefficients(w, &a, &b);
  // Invert V = [a -b; b a]: V^-1 = [a b; -b a] / (a^2 + b^2).
  const double det = a * a + b * b;
  return {(a * pose.x + b * pose.y) / det, (-b * pose.x + a * pose.y) / det, w};
}

Pose2 interpolate(const Pose2& a, const Pose2& b, double t) {
  const Twist2 delta = log_se2(between(a, b));
  return compose(a, exp_se2({delta.vx * t, delta.vy * t, delta.omega * t}));
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::optional<double> circular_mean(std::span<const double> angles, std::span<const double> weights) {
  if (angles.empty() || (!weights.empty() && weights.size() != angles.size())) {
    return std::nullopt;
  }
  double sum_sin = 0.0;
  double sum_cos = 0.0;
  double sum_weight = 0.0;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!std::isfinite(w) || w < 0.0 || !std::isfinite(angles[i])) {
      return std::nullopt;
    }
    sum_sin += w * std::sin(angles[i]);
    sum_cos += w * std::cos(angles[i]);
    sum_weight += w;
  }
  // Mean resultant length below 1e-9 of the total weight: no defined direction.
  if (sum_weight <= 0.0 || std::hypot(sum_sin, sum_cos) <= 1e-9 * sum_weight) {
    return std::nullopt;
  }
  return wrap_angle(std::atan2(sum_sin, sum_cos));
}

}  // namespace slamer

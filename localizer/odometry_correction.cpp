#include "localizer/odometry_correction.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

namespace {
constexpr double kTurnLength = 0.3;  // [m per rad] how much a radian of turning counts as driving, for forgetting
constexpr double kRidgeTrans =
    0.01;  // [m^2] prior weight against a bias per metre (about 4 m of straight driving at 40 Hz)
constexpr double kRidgeRot = 0.01;      // [rad^2]
constexpr double kMaxBiasTrans = 0.15;  // [rad/m] (8.6 deg/m: a radius error near 2.5 %)
constexpr double kMaxBiasRot = 0.15;    // [rad/rad]
constexpr double kMaxResidual = 0.05;   // [rad] per scan: more is a relocalization, not odometry error
}  // namespace

void OdometryCorrection::observe(const OdometryIncrement& u, double estimated_turn) {
  if (!enabled()) {
    return;
  }
  const double rot = u.rot1 + u.rot2;
  const double residual = estimated_turn - rot;
  if (!std::isfinite(residual) || std::abs(residual) > kMaxResidual) {
    return;
  }
  const double travel = std::abs(u.trans) + kTurnLength * std::abs(rot);
  const double keep = std::exp(-travel / memory_);
  sxx_ = keep * sxx_ + u.trans * u.trans;
  sxy_ = keep * sxy_ + u.trans * rot;
  syy_ = keep * syy_ + rot * rot;
  sxr_ = keep * sxr_ + u.trans * residual;
  syr_ = keep * syr_ + rot * residual;
  // Ridge regression: (S + R) b = s.
  const double a = sxx_ + kRidgeTrans;
  const double d = syy_ + kRidgeRot;
  const double det = a * d - sxy_ * sxy_;
  b_trans_ = std::clamp((d * sxr_ - sxy_ * syr_) / det, -kMaxBiasTrans, kMaxBiasTrans);
  b_rot_ = std::clamp((a * syr_ - sxy_ * sxr_) / det, -kMaxBiasRot, kMaxBiasRot);
}

OdometryIncrement OdometryCorrection::correct(const OdometryIncrement& u) const {
  if (!enabled()) {
    return u;
  }
  // Half of the turn before the translation, half after (the mid-point heading).
  const double extra = b_trans_ * u.trans + b_rot_ * (u.rot1 + u.rot2);
  return {u.rot1 + 0.5 * extra, u.trans, u.rot2 + 0.5 * extra};
}

void OdometryCorrection::reset() {
  sxx_ = sxy_ = syy_ = sxr_ = syr_ = 0.0;
  b_trans_ = b_rot_ = 0.0;
}

}  // namespace slamer

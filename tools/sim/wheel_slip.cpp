#include "tools/sim/wheel_slip.hpp"

#include <cmath>

namespace slamer {

namespace {
constexpr double kSlipTimeConstant = 1.0;  // [s] how long the random turn slip stays correlated
}  // namespace

void WheelSlip::apply(double dt, double omega, double* left, double* right, std::mt19937& rng) {
  std::normal_distribution<double> standard(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (options_.turn_slip != 0.0 || options_.turn_slip_stddev > 0.0) {
    if (options_.turn_slip_stddev > 0.0) {
      const double a = std::exp(-dt / kSlipTimeConstant);
      random_slip_ = a * random_slip_ + std::sqrt(1.0 - a * a) * standard(rng);
    }
    // The wheels spin more than the turn needs (skid): the differential grows.
    const double excess = (options_.turn_slip + options_.turn_slip_stddev * random_slip_) * std::abs(omega);
    const double half_difference = 0.5 * (*right - *left) * excess;
    *left -= half_difference;
    *right += half_difference;
  }
  if (options_.bump_rate > 0.0 && options_.bump_duration > 0.0) {
    if (bump_left_ <= 0.0 && uniform(rng) < options_.bump_rate * dt) {
      bump_left_ = options_.bump_duration;
      bump_on_left_ = uniform(rng) < 0.5;
      bump_speed_ = (uniform(rng) < 0.5 ? -1.0 : 1.0) * options_.bump_travel / options_.bump_duration;
    }
    if (bump_left_ > 0.0) {
      const double extra = bump_speed_ * std::min(dt, bump_left_);
      (bump_on_left_ ? *left : *right) += extra;
      bump_left_ -= dt;
    }
  }
}

}  // namespace slamer

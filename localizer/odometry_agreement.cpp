#include "localizer/odometry_agreement.hpp"

#include <cmath>

namespace slamer {

void OdometryAgreement::add(int64_t utime, const Pose2& before, const Pose2& after, double odometry_forward) {
  if (!(window_ > 0.0)) {
    return;
  }
  const double forward = (after.x - before.x) * std::cos(before.theta) + (after.y - before.y) * std::sin(before.theta);
  const double step = forward - odometry_forward;
  if (!std::isfinite(step)) {
    return;
  }
  // Time going back (a replayed log from the top) starts over.
  if (!steps_.empty() && utime < steps_.back().utime) {
    reset();
  }
  steps_.push_back({utime, step, std::abs(odometry_forward)});
  const auto window = static_cast<int64_t>(window_ * 1e6);
  while (!steps_.empty() && steps_.front().utime <= utime - window) {
    steps_.pop_front();
  }
  // Summed afresh (at most a few hundred steps): no drift from adding and subtracting.
  double travel = 0.0;
  for (const Step& s : steps_) {
    travel += s.travel;
  }
  while (steps_.size() > 1 && travel - steps_.front().travel >= distance_) {
    travel -= steps_.front().travel;
    steps_.pop_front();
  }
  sum_ = 0.0;
  for (const Step& s : steps_) {
    sum_ += s.disagreement;
  }
}

void OdometryAgreement::reset() {
  steps_.clear();
  sum_ = 0.0;
}

}  // namespace slamer

#include "drivers/wheels/wheel_odometry.hpp"

#include <algorithm>
#include <cmath>

namespace slamer::tfrog {

std::array<int64_t, 2> TickUnwrapper::feed(const std::array<int16_t, 2>& raw) {
  std::array<int64_t, 2> delta{};
  if (previous_) {
    for (std::size_t i = 0; i < 2; ++i) {
      delta[i] = static_cast<int16_t>(static_cast<uint16_t>(raw[i]) - static_cast<uint16_t>((*previous_)[i]));
      cumulative_[i] += delta[i];
    }
  }
  previous_ = raw;
  return delta;
}

double DiffDriveIntegrator::travel(int motor, int64_t ticks) const {
  const auto i = static_cast<std::size_t>(motor);
  return 2.0 * M_PI * k_.radius[i] * static_cast<double>(ticks) / k_.counts_per_wheel_rev[i];
}

void DiffDriveIntegrator::add(const std::array<int64_t, 2>& delta, double dt) {
  const double right = travel(0, delta[0]);
  const double left = travel(1, delta[1]);
  const double ds = (right + left) / 2.0;
  const double dtheta = (right - left) / k_.tread;
  if (integration_ == Integration::kExactArc) {
    pose_ = compose(pose_, exp_se2(Twist2{ds, 0.0, dtheta}));
  } else {
    pose_.x += ds * std::cos(pose_.theta);
    pose_.y += ds * std::sin(pose_.theta);
    pose_.theta = wrap_angle(pose_.theta + dtheta);
  }
  distance_ += std::fabs(ds);
  if (dt > 0.0) {
    v_ = ds / dt;
    omega_ = dtheta / dt;
  }
}

FrameStamp FrameClock::stamp(int64_t receive_utime, int frames_behind) {
  const int64_t measured = receive_utime - latency_ - static_cast<int64_t>(frames_behind) * period_;
  FrameStamp out;
  if (!last_) {
    out.utime = measured;
    last_ = measured;
    return out;
  }
  const double elapsed = static_cast<double>(measured - *last_);
  // A gap counts as lost frames only past 1.7 periods: read-time jitter up to 3.5 ms is not a loss.
  const auto steps =
      static_cast<int64_t>(std::floor((elapsed + 0.3 * static_cast<double>(period_)) / static_cast<double>(period_)));
  if (steps > 200 || elapsed < -10.0 * static_cast<double>(period_)) {  // a long gap or a clock jump: restart
    out.utime = measured;
    out.lost = steps > 200 ? steps - 1 : 0;
  } else {
    const int64_t n = std::max<int64_t>(steps, 1);
    out.lost = n - 1;
    const int64_t predicted = *last_ + n * period_;
    // Arrival bounds the send time from above: an early arrival pulls the
    // estimate back at once, late arrivals (latency jitter) only slowly.
    out.utime =
        measured < predicted ? std::max(measured, *last_ + period_ / 2) : predicted + (measured - predicted) / 32;
  }
  lost_total_ += out.lost;
  last_ = out.utime;
  return out;
}

}  // namespace slamer::tfrog

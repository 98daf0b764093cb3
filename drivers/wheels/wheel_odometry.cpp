#include "drivers/wheels/wheel_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace slamer::tfrog {

std::array<int64_t, 2> TickUnwrapper::feed(const std::array<int16_t, 2>& raw) {
  std::array<int64_t, 2> delta{};
  if (previous_) {
    for (std::size_t i = 0; i < 2; ++i) {
      delta[i] = static_cast<int16_t>(static_cast<uint16_t>(raw[i]) - static_cast<uint16_t>((*previous_)[i]));
      if (either_ && std::abs(static_cast<int64_t>(raw[i])) < std::abs(delta[i])) {
        delta[i] = raw[i];  // the board restarted at 0
      }
      cumulative_[i] += delta[i];
    }
  }
  either_ = false;
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
  const int64_t nominal = last_ ? *last_ + period_ : measured;
  const int64_t delay = measured - nominal;                        // against "no frame lost"
  if (!last_ || delay > 200 * period_ || delay < -10 * period_) {  // first frame, long gap or clock jump
    out.utime = measured;
    out.lost = last_ && delay > 0 ? delay / period_ : 0;
    late_frames_ = 0;
  } else if (delay < 0) {
    // Arrival bounds the send time from above: an early arrival pulls the estimate back at once.
    out.utime = std::max(measured, *last_ + period_ / 2);
    late_frames_ = 0;
  } else {
    // Late arrivals (read latency) move the estimate only slowly. Frames that
    // stay at least ~a period late for kConfirm frames in a row mean frames
    // were lost: one late read alone is not a loss.
    out.utime = nominal + delay / 32;
    if (delay >= period_ * 7 / 10) {
      min_late_ = late_frames_ == 0 ? delay : std::min(min_late_, delay);
      if (++late_frames_ >= kConfirm) {
        const int64_t lost = (min_late_ + period_ * 3 / 10) / period_;
        out.lost = lost;
        out.utime = std::min(out.utime + lost * period_, measured);
        late_frames_ = 0;
      }
    } else {
      late_frames_ = 0;
    }
  }
  lost_total_ += out.lost;
  last_ = out.utime;
  return out;
}

}  // namespace slamer::tfrog

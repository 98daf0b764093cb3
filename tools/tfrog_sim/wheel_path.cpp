#include "tools/tfrog_sim/wheel_path.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace slamer::tfrog {

std::vector<PathSegment> parse_path(const std::string& spec) {
  std::vector<PathSegment> segments;
  std::istringstream in(spec);
  std::string item;
  while (std::getline(in, item, ';')) {
    if (item.empty()) {
      continue;
    }
    PathSegment s;
    char c1 = 0;
    char c2 = 0;
    std::istringstream fields(item);
    if (!(fields >> s.v >> c1 >> s.omega >> c2 >> s.duration) || c1 != ',' || c2 != ',' || !(s.duration >= 0.0) ||
        !std::isfinite(s.v) || !std::isfinite(s.omega)) {
      throw std::runtime_error("bad path segment '" + item + "' (want v,omega,duration)");
    }
    segments.push_back(s);
  }
  return segments;
}

PathPlayer::PathPlayer(std::vector<PathSegment> segments, const Kinematics& kinematics)
    : segments_(std::move(segments)), k_(kinematics) {}

std::array<double, 2> PathPlayer::step(double dt) {
  std::array<double, 2> counts{};
  double left = dt;
  while (left > 0.0 && !done()) {
    const PathSegment& s = segments_[index_];
    const double h = std::min(left, s.duration - in_segment_);
    const double half = s.omega * k_.tread / 2.0;
    const std::array<double, 2> wheel = {(s.v + half) / k_.radius[0], (s.v - half) / k_.radius[1]};
    for (std::size_t i = 0; i < 2; ++i) {
      counts[i] += wheel[i] * h * k_.counts_per_wheel_rev[i] / (2.0 * M_PI);
    }
    truth_ = compose(truth_, exp_se2(Twist2{s.v * h, 0.0, s.omega * h}));
    distance_ += std::fabs(s.v) * h;
    in_segment_ += h;
    left -= h;
    if (in_segment_ >= s.duration - 1e-12) {
      ++index_;
      in_segment_ = 0.0;
    }
  }
  return counts;
}

EncoderFollower::EncoderFollower(const Kinematics& kinematics) {
  for (std::size_t i = 0; i < 2; ++i) {
    sign_[i] = kinematics.radius[i] < 0 ? -1 : 1;
  }
}

void EncoderFollower::add(int64_t utime, int64_t left_ticks, int64_t right_ticks) {
  const std::array<int64_t, 2> wheel = {right_ticks, left_ticks};  // motor 0 = right, motor 1 = left
  if (samples_++ == 0) {
    first_ = wheel;
    last_utime_ = utime;
    return;
  }
  ramp_ticks_ = std::clamp<int64_t>((utime - last_utime_) / 1000, 1, 100);
  ramp_done_ = 0;
  last_utime_ = std::max(last_utime_, utime);
  for (std::size_t i = 0; i < 2; ++i) {
    target_[i] = sign_[i] * (wheel[i] - first_[i]);
    ramp_start_[i] = commanded_[i];
  }
}

std::array<double, 2> EncoderFollower::step() {
  std::array<double, 2> counts{};
  if (ramp_done_ >= ramp_ticks_) {
    return counts;
  }
  ++ramp_done_;
  for (std::size_t i = 0; i < 2; ++i) {
    // Whole counts: the board's floating count stays exact and ends on the target.
    const int64_t delta = target_[i] - ramp_start_[i];
    const int64_t next = ramp_start_[i] + (delta * ramp_done_) / ramp_ticks_;
    counts[i] = static_cast<double>(next - commanded_[i]);
    commanded_[i] = next;
  }
  return counts;
}

}  // namespace slamer::tfrog

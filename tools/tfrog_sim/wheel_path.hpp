// Wheel motion for the emulators: a scripted drive (segments of constant
// (v, omega) for a duration, played back as motor count increments through the
// robot's signed radii, with the true pose integrated exactly:
// constant-curvature arcs), or the wheel_encoders_t counts another program
// publishes (EncoderFollower: slamer-sim's, so the real driver sees the
// simulated robot's wheels).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "drivers/wheels/ypspur_params.hpp"

namespace slamer::tfrog {

struct PathSegment {
  double v = 0.0;         // [m/s]
  double omega = 0.0;     // [rad/s]
  double duration = 0.0;  // [s]
};
// "v,omega,duration;v,omega,duration;..."; throws std::runtime_error naming the bad segment.
std::vector<PathSegment> parse_path(const std::string& spec);

class PathPlayer {
 public:
  PathPlayer(std::vector<PathSegment> segments, const Kinematics& kinematics);
  // Advances dt [s]; returns motor count increments (fractional) over it.
  std::array<double, 2> step(double dt);
  bool done() const { return index_ >= segments_.size(); }
  const Pose2& truth() const { return truth_; }
  double distance() const { return distance_; }

 private:
  std::vector<PathSegment> segments_;
  Kinematics k_;
  std::size_t index_ = 0;
  double in_segment_ = 0.0;
  Pose2 truth_;
  double distance_ = 0.0;
};

// Follows cumulative wheel counts (wheel_encoders_t: ticks[0] left, ticks[1]
// right, forward-positive, counts per wheel turn = COUNT_REV * GEAR of the same
// robot) with the board's motors (motor 0 right, motor 1 left, each counting
// with the sign of its RADIUS). Counts are relative to the first sample. Each
// sample is reached by a ramp over its interval since the previous one (1 to
// 100 ticks of 1 ms) in whole counts per tick, so the board's counts are exact.
class EncoderFollower {
 public:
  explicit EncoderFollower(const Kinematics& kinematics);
  void add(int64_t utime, int64_t left_ticks, int64_t right_ticks);
  // One 1 ms tick: motor count increments.
  std::array<double, 2> step();
  int64_t samples() const { return samples_; }

 private:
  std::array<int64_t, 2> sign_{};
  std::array<int64_t, 2> first_{};       // wheel ticks of the first sample, per motor
  std::array<int64_t, 2> commanded_{};   // motor counts reached so far
  std::array<int64_t, 2> ramp_start_{};  // motor counts where the ramp began
  std::array<int64_t, 2> target_{};      // motor counts of the last sample
  int64_t ramp_ticks_ = 0;
  int64_t ramp_done_ = 0;
  int64_t last_utime_ = 0;
  int64_t samples_ = 0;
};

}  // namespace slamer::tfrog

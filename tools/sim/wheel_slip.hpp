// What the wheel encoders of a real differential-drive base see beyond the
// geometry the odometry assumes (issue 9, "realistic simulation"): wheel
// radius and tread errors are applied by the simulator; this adds
//  * slip that grows with the yaw rate: the wheels' differential travel
//    exceeds the body's turn by `turn_slip` per rad/s (systematic) plus a
//    slowly varying random part (an Ornstein-Uhlenbeck process with a 1 s
//    time constant) of standard deviation `turn_slip_stddev` per rad/s;
//  * occasional bumps: Poisson events (`bump_rate` per second) during which
//    one wheel, picked at random, reports `bump_travel` metres of extra travel
//    (random sign) spread over `bump_duration` seconds.
// Deterministic for a given random stream; with all four options zero it
// draws no random numbers, so older runs stay byte-identical.
#pragma once

#include <random>

namespace slamer {

struct WheelSlipOptions {
  double turn_slip = 0.0;         // [1/(rad/s)] systematic excess differential travel per rad/s of yaw rate
  double turn_slip_stddev = 0.0;  // [1/(rad/s)] random part of it (correlated over about 1 s)
  double bump_rate = 0.0;         // [1/s] mean bumps per second
  double bump_travel = 0.01;      // [m] extra travel of the bumped wheel per bump
  double bump_duration = 0.05;    // [s] over which a bump's extra travel is reported
};

class WheelSlip {
 public:
  explicit WheelSlip(const WheelSlipOptions& options) : options_(options) {}
  // Extra travel [m] of the left and right wheel during a step of `dt`
  // seconds in which the base turned at `omega` [rad/s] and the wheels
  // travelled `left` and `right` metres.
  void apply(double dt, double omega, double* left, double* right, std::mt19937& rng);

 private:
  WheelSlipOptions options_;
  double random_slip_ = 0.0;  // the OU state, unit variance
  double bump_left_ = 0.0;    // time left of the current bump [s]
  double bump_speed_ = 0.0;   // its extra travel per second [m/s], signed
  bool bump_on_left_ = false;
};

}  // namespace slamer

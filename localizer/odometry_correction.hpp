// Online correction of the odometry's systematic heading error (issue 9: "a
// correction of the odometry increment" from the scans). Uncalibrated wheels
// (radius off by +-1 %, tread off) turn the odometry's heading by a fixed
// amount per metre driven and per radian turned (3-5 deg/m on real robots),
// which a particle filter with motion noise sized for good odometry can only
// follow by lagging behind. This learns, from the filter's own estimate while
// it is sure (status OK, the scan fits), the heading the estimate turned
// beyond the odometry per scan as
//     residual = b_trans * trans + b_rot * rot
// by exponentially forgetting ridge regression (memory in metres of driving
// and radians of turning), and adds that to later increments. Bounded, so a
// bad stretch cannot teach it more than max_bias.
#pragma once

#include "localizer/motion_model.hpp"

namespace slamer {

class OdometryCorrection {
 public:
  // `memory`: how far back observations count [m, and rad x 0.3 m]; 0 turns it off.
  explicit OdometryCorrection(double memory) : memory_(memory) {}

  bool enabled() const { return memory_ > 0.0; }
  // One scan's odometry increment and how far the estimate's heading turned over it [rad].
  void observe(const OdometryIncrement& u, double estimated_turn);
  // The increment with the learned heading error taken out.
  OdometryIncrement correct(const OdometryIncrement& u) const;
  void reset();
  double heading_per_metre() const { return b_trans_; }  // [rad/m]
  double heading_per_radian() const { return b_rot_; }   // [rad/rad]

 private:
  double memory_;
  double sxx_ = 0.0, sxy_ = 0.0, syy_ = 0.0;  // sums of f f^T (trans, rot)
  double sxr_ = 0.0, syr_ = 0.0;              // sums of f * residual
  double b_trans_ = 0.0, b_rot_ = 0.0;
};

}  // namespace slamer

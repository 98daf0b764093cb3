// Sampling motion model of a differential-drive base from odometry (paper
// Eq. (5), u ~ N(u_t, Sigma_u)): the odometry increment between two times is
// decomposed into rotate / translate / rotate (Probabilistic Robotics 5.4),
// each perturbed with a standard deviation that grows with the increment.
//
// A heavy tail on the heading (issue 9): a wheel that bumps over a cable or
// slips in a turn turns the odometry's heading by a degree or so within one
// scan, 50 standard deviations of the alphas' per-scan noise. No particle is
// then near the true heading, and the scans pull the cloud there only over
// dozens of scans (LFM on paper_indoor with the realistic simulated odometry:
// 3.9 cm mean error against 3.5 with odometry that neither bumps nor slips).
// So at each scan's prediction in which the base moved, heading_slip_fraction
// of the particles get extra heading noise of heading_slip_sigma: the few
// that land near the truth after a slip outweigh the rest at the next scan.
#pragma once

#include <random>

#include "common/geometry/se2.hpp"
#include "localizer/localizer_options.hpp"

namespace slamer {

struct OdometryIncrement {
  double rot1 = 0.0;
  double trans = 0.0;
  double rot2 = 0.0;
};

// The increment from odometry pose `from` to `to` (odometry frame).
OdometryIncrement decompose(const Pose2& from, const Pose2& to);

// `pose` moved by the increment, which took `seconds`, with noise drawn from
// `rng`. The standard deviations are multiplied by `gain` (>= 1: adaptive
// noise), and (gain - 1) x noise_floor_trans / _rot is added, so that a zero
// increment still spreads the particles when the scans say the pose is off;
// times `sqrt(seconds / noise_floor_interval)` for increments shorter than
// that interval (a random walk's spread, the same per second at any scan rate).
Pose2 sample_motion(const Pose2& pose, const OdometryIncrement& u, const MotionOptions& options, std::mt19937& rng,
                    double gain = 1.0, double seconds = 0.0);

}  // namespace slamer

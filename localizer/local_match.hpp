// Local scan matching against the likelihood field (issue 9: "a scan-matching
// correction of the odometry increment"; the correlative search of Olson,
// "Real-time correlative scan matching", ICRA 2009, on the LFM field of
// Eqs. (10)-(13)). Where the odometry disagrees with the scans (a lost sign of
// translation, a turn measured 27 deg short, a wheel bump), the particles the
// motion model moved are all in the wrong place and no reweighting can bring
// them back: this finds the pose near the prediction that explains the scan
// best, so the filter can put particles there (ParticleFilter: a local
// Mixture-MCL proposal, used only while the prediction fits poorly).
//
// The search is over the sensor's pose: every heading of a window, then every
// translation of a grid, scored with a thinned scan (sum of the field's
// log-likelihoods of the end points); the best, and the best of the poses
// apart from it, are refined by coordinate ascent with halving steps, within
// the window. Pure: no state, no randomness.
#pragma once

#include "common/map/likelihood_field.hpp"
#include "localizer/scan_fit.hpp"

namespace slamer {

struct LocalMatchWindow {
  double shift = 0.5;        // [m] the search reaches this far in x and y from the prediction
  double turn = 0.5;         // [rad] and this far in heading
  double shift_step = 0.1;   // [m] coarse grid (rounded to whole cells of the map)
  double turn_step = 0.025;  // [rad]
  int beams = 90;            // the scan thinned to about this many end points
  // The runner-up is the best local maximum of the grid at least this far
  // from the best pose (in translation, or in heading), refined in the same way.
  double separation = 0.25;       // [m]
  double separation_turn = 0.15;  // [rad]
};

struct LocalMatch {
  Pose2 pose;                  // of the base (mount taken back out)
  double mean_log_likelihood;  // per end point used, at `pose`
  // Another place in the window the scan fits best at (`pose` if the window
  // holds none apart from it): the caller compares the two, since a scan
  // that fits two places equally well does not say which.
  Pose2 runner_up;
};

// The best base pose within `window` of `predicted` for the scan `points`
// (sensor frame, cells; see ScanPoints), the sensor at `mount` on the base.
// With no points, `predicted` and 0.
LocalMatch match_locally(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                         const Pose2& predicted, const LocalMatchWindow& window);

// Coordinate ascent from the base pose `start`, as the match refines its best
// pose: first steps of `shift` [m] and `turn` [rad], halving three times,
// never further than 4 x those from `start`; the scan thinned to about
// `beams`. Where a pose drawn at random (a global proposal) is nearest the
// scan's fit, not where the draw put it.
Pose2 climb_locally(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount, const Pose2& start,
                    double shift, double turn, int beams);

}  // namespace slamer

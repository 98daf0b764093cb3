// Whether the estimate still moves as the odometry says (issue 9's honest
// status). A filter whose scans fit can still slide: in a corridor past doors
// the map has open and the truth shut, the scan fits better a little further
// back, and scan after scan the estimate is pulled behind the robot while the
// fit stays good (generated worlds 103014, 104000: 1-3 m off, saying OK). No
// single scan shows it; over time it shows as the estimate travelling along
// its heading less (or more) than the wheels did. This sums, over the last
// `window` seconds, each update's
//     (estimate after - estimate before) . (cos theta, sin theta) - odometry forward travel
// with theta the heading before: signed, so a correction that is undone
// cancels, and along the heading, so the odometry's heading drift (3-5 deg/m
// uncalibrated) does not enter. The window also ends `distance` metres of
// the odometry's travel back: the odometry's scale error grows with the
// distance (a few per cent on real logs: csail over 10 s of its 1 m steps is
// 94 m and 3 m off, with the estimate right), so the sum is taken only where
// the odometry can be trusted to a fraction of the bar. Uncalibrated wheels
// (radius +-1-2 %) and bumps give a few centimetres to 0.3 m over 10 s on the
// generated worlds; a slide 0.5-3 m. Whether the map or the odometry is wrong
// the scans cannot tell, so the status says UNCERTAIN, not LOST, and nothing
// else changes.
#pragma once

#include <cstdint>
#include <deque>

#include "common/geometry/se2.hpp"

namespace slamer {

class OdometryAgreement {
 public:
  // The last `window` seconds and at most the last `distance` metres of the
  // odometry's travel (the steps that make it up, the oldest just reaching
  // it); `window` 0 turns it off (along_track() stays 0).
  OdometryAgreement(double window, double distance) : window_(window), distance_(distance) {}

  // One update at `utime`: the estimate before and after it, and the
  // odometry's forward travel in between [m] (negative backwards).
  void add(int64_t utime, const Pose2& before, const Pose2& after, double odometry_forward);
  // The signed sum over the window [m]: > 0 the estimate went further than
  // the odometry, < 0 less far.
  double along_track() const { return sum_; }
  // A new start (a pose given by hand, global localization, a jump the filter made on purpose).
  void reset();

 private:
  struct Step {
    int64_t utime;
    double disagreement;
    double travel;  // |odometry forward|
  };
  double window_;
  double distance_;
  std::deque<Step> steps_;
  double sum_ = 0.0;
};

}  // namespace slamer

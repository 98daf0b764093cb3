// Along-track evidence for the localizer's status (issue 9, "an honest
// status"). In a corridor the scan pins the pose across it and in heading but
// barely along it, so a cloud that follows odometry with a scale error slides
// along the corridor while every beam still ends on a wall: the scan fit
// (scan_fit.hpp) stays high and the cloud stays tight. On the CMU Wean logs
// (on a mirrored map, read wrongly until 2026-12-06) two seeds of the filter
// parted by up to 1.15 m along a corridor, both saying OK, while a pose
// 0.6-1.0 m along the heading scored 10-40 nats better over 90 beams than the
// estimate in most of those scans; on the generated worlds (suite seed 3) it
// takes SLFM's far-off scans flagged from 70 to 83 %; on the CARMEN logs,
// whose estimates are right, a scan scores a pose that far along better by
// even 2 nats in 0.2-0.5 % of the scans, never 10 in a row. This
// scores the scan on the likelihood field (the LFM's, Eqs. (10)-(13)) at the
// estimate and at poses shifted along its heading, so the status can say
// UNCERTAIN while the scans keep preferring a pose elsewhere on that line,
// and, once the position along the line was in doubt, until a scan fits every
// shifted pose clearly worse than the estimate (the margin: it pins it).
#pragma once

#include "common/geometry/se2.hpp"
#include "common/map/likelihood_field.hpp"
#include "localizer/scan_fit.hpp"

namespace slamer {

struct AlongTrackShifts {
  double nearest = 0.4;   // [m] shifts from this far ...
  double farthest = 1.0;  // [m] ... to this far, forward and back
  double step = 0.2;      // [m]
  int beams = 90;         // the scan thinned to about this many end points
};

struct AlongTrackPreference {
  // [m] along the heading (negative: behind) of the best-scoring pose; 0 if none beats the estimate.
  double shift = 0.0;
  double gain = 0.0;  // its log-likelihood minus the estimate's, per end point used (>= 0)
  // The estimate's log-likelihood minus that of the best shifted pose, per end
  // point used: > 0 when every shift fits worse, so the scan pins the position
  // along the heading; about 0 in a corridor; -gain when a shift fits better.
  double margin = 0.0;
};

// The pose shifted along `base`'s heading (by `shifts`) that scores the scan
// `points` (sensor frame, cells; see ScanPoints) best on `field`, against
// `base` itself, the sensor at `mount` on the base. With no points: none.
AlongTrackPreference along_track_preference(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                                            const Pose2& base, const AlongTrackShifts& shifts);

}  // namespace slamer

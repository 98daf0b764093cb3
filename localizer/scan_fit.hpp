// Scan-fit evidence for the localizer's status (issue 9, "an honest status"):
// the fraction of a scan's valid beams whose end point, placed in the map from
// a pose, lies within `fit_distance` of an obstacle of the map. At the true
// pose this is high (range noise and unmapped objects take a few beams away);
// a cloud that is confident but wrong cannot raise it, because it depends on
// the one pose the filter reports, not on the particles' spread.
#pragma once

#include <vector>

#include "common/geometry/se2.hpp"
#include "common/map/distance_field.hpp"
#include "common/map/likelihood_field.hpp"

namespace slamer {

// Beam end points in the sensor frame, in grid cells.
struct ScanPoints {
  std::vector<float> x;
  std::vector<float> y;
};

// The sensor pose in grid cells: translation in cells, heading in radians.
Pose2 sensor_in_cells(const GridGeometry& geometry, const Pose2& base, const Pose2& mount);

// Fraction of `points` (every `step`-th) within `fit_distance` [m] of an
// obstacle, for a sensor at `sensor` (sensor_in_cells). 0 for no points;
// points off the map do not fit.
double scan_fit(const DistanceField& obstacles, const ScanPoints& points, const Pose2& sensor, double fit_distance,
                std::size_t step = 1);

// Every `step`-th of `points` (a step of 0 as 1): a scan thinned once for the
// many poses a search scores it at.
ScanPoints thinned_points(const ScanPoints& points, std::size_t step);

// Sum of the likelihood field's log-likelihoods of `points` for a sensor at
// `sensor` (sensor_in_cells), off-map points at the field's off-map value:
// how global proposals and local matches score a pose.
double field_log_likelihood(const LikelihoodField& field, const ScanPoints& points, const Pose2& sensor);

}  // namespace slamer

// Spatial line objects: lines with no physical shape that the scan passes
// through, such as an open doorway or a no-entry line (paper Sec. VI-B).
//
// A candidate joins two scan points (each unordered pair at most once) whose
// distance is within limits and whose orientation agrees with the physical
// lines' orientation histogram. It is kept when the beams between its end
// points pass through it: their points lie at least pass_margin beyond the
// line (perpendicular distance, far side from the sensor) or they returned
// nothing. Those beams not lying on the line is what "not covered" means.
//
// Only points where the scan can go past are end points: the next beam
// after a left end (previous before a right end) returned nothing or lies at
// least pass_margin away. That is exact for the rule above (a neighbour
// closer than pass_margin cannot be pass_margin beyond any line through the
// point) and keeps the search far below the all-pairs O(P^2) of the
// published implementation.
#pragma once

#include <vector>

#include "recognizer/orientation_histogram.hpp"
#include "recognizer/recognizer_options.hpp"
#include "recognizer/scan_points.hpp"
#include "recognizer/segment_merge.hpp"

namespace slamer {

struct SpatialLine {
  Segment2 segment;
  int first_beam = 0;
  int last_beam = 0;
  int passing_beams = 0;
  int considered_beams = 0;  // beams between the ends that told something
};

// Candidates that pass, before merging, ordered by (first_beam, last_beam).
std::vector<SpatialLine> spatial_candidates(const PreparedScan& scan, double angle_increment,
                                            const OrientationHistogram& histogram, const RecognizerOptions& options);

// Merges near-duplicates (end points within merge_distance, either way round);
// each group is represented by its member with the most passing beams.
std::vector<SpatialLine> merge_spatial_lines(const std::vector<SpatialLine>& candidates,
                                             const RecognizerOptions& options);

}  // namespace slamer

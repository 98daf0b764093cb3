// Physical line objects: straight runs of scan points (walls, closed doors,
// glass, fences). The probabilistic Hough transform (OpenCV) finds
// candidates in an image of the scan; each is refitted to its supporting
// points (true point-to-segment distance, right for every orientation),
// near-duplicates are merged order-independently, and each line gets its
// coverage: the fraction of its length the supporting points occupy (a wall
// is covered, glass and fences only partly: the paper's "point rate").
#pragma once

#include <vector>

#include "recognizer/recognizer_options.hpp"
#include "recognizer/scan_points.hpp"
#include "recognizer/segment_merge.hpp"

namespace slamer {

struct PhysicalLine {
  Segment2 segment;
  int points = 0;         // supporting scan points
  double coverage = 0.0;  // in [0, 1]
};

// Hough segments of the scan image, in metres (sensor frame), in OpenCV's order.
std::vector<Segment2> hough_segments(const PreparedScan& scan, const RecognizerOptions& options);

// Refits, merges and measures candidate segments; the result is sorted and
// does not depend on the candidates' order.
std::vector<PhysicalLine> refine_physical_lines(const PreparedScan& scan, const std::vector<Segment2>& candidates,
                                                const RecognizerOptions& options);

}  // namespace slamer

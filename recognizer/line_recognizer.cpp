#include "recognizer/line_recognizer.hpp"

#include <cmath>

#include "recognizer/orientation_histogram.hpp"
#include "recognizer/physical_lines.hpp"
#include "recognizer/scan_points.hpp"
#include "recognizer/spatial_lines.hpp"

namespace slamer {

int matching_rule(LineKind kind, double coverage, double length, const RecognizerOptions& options) {
  for (std::size_t r = 0; r < options.rules.size(); ++r) {
    const ClassRule& rule = options.rules[r];
    if (rule.kind == kind && length >= rule.min_length && length <= rule.max_length &&
        (kind == LineKind::kSpatial || (coverage >= rule.min_coverage && coverage <= rule.max_coverage))) {
      return static_cast<int>(r);
    }
  }
  return -1;
}

std::vector<float> classify(LineKind kind, double coverage, double length, const RecognizerOptions& options) {
  const std::size_t n = options.classes.size();
  const int r = matching_rule(kind, coverage, length, options);
  if (r < 0) {
    return std::vector<float>(n, static_cast<float>(1.0 / static_cast<double>(n)));
  }
  const ClassRule& rule = options.rules[static_cast<std::size_t>(r)];
  std::vector<double> weights(n, options.floor);
  for (std::size_t c = 0; c < n; ++c) {
    const auto it = rule.probs.find(options.classes[c]);
    if (it != rule.probs.end()) {
      weights[c] = it->second;
    }
  }
  double sum = 0.0;
  for (const double w : weights) {
    sum += w;
  }
  std::vector<float> probs(n);
  for (std::size_t c = 0; c < n; ++c) {
    probs[c] = static_cast<float>(sum > 0.0 ? weights[c] / sum : 1.0 / static_cast<double>(n));
  }
  return probs;
}

std::vector<RecognizedLine> LineRecognizer::recognize_with_features(const LaserScan& scan) const {
  std::vector<RecognizedLine> lines;
  const PreparedScan prepared = prepare_scan(scan);
  if (prepared.hits.size() < 2) {
    return lines;  // nothing to see: no lines, no crash
  }
  const std::vector<PhysicalLine> physical =
      refine_physical_lines(prepared, hough_segments(prepared, options_), options_);
  OrientationHistogram histogram(options_.histogram_bins);
  for (const PhysicalLine& line : physical) {
    const Eigen::Vector2d d = line.segment.b - line.segment.a;
    histogram.add(std::atan2(d.y(), d.x()), d.norm());
    lines.push_back({{LineKind::kPhysical, line.segment.a, line.segment.b, line.points,
                      classify(LineKind::kPhysical, line.coverage, d.norm(), options_), -1},
                     line.coverage});
  }
  const std::vector<SpatialLine> spatial =
      merge_spatial_lines(spatial_candidates(prepared, scan.angle_increment, histogram, options_), options_);
  for (const SpatialLine& line : spatial) {
    const double length = (line.segment.b - line.segment.a).norm();
    lines.push_back({{LineKind::kSpatial, line.segment.a, line.segment.b, 0,
                      classify(LineKind::kSpatial, 0.0, length, options_), -1},
                     0.0});
  }
  return lines;
}

LineObjectSet LineRecognizer::recognize(const LaserScan& scan) const {
  LineObjectSet result;
  result.utime = scan.utime;
  result.seq = scan.seq;
  result.class_names = options_.classes;
  for (RecognizedLine& line : recognize_with_features(scan)) {
    result.objects.push_back(std::move(line.object));
  }
  return result;
}

}  // namespace slamer

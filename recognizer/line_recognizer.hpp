// The line-object recognizer (paper Sec. VI-B, made correct): physical lines
// from the probabilistic Hough transform of a scan image, their orientation
// histogram, spatial lines the scan passes through, and class probabilities
// for each from configurable rules. Pure: a scan in, objects out.
#pragma once

#include "common/semantic/objects.hpp"
#include "common/sensors/laser_scan.hpp"
#include "recognizer/recognizer_options.hpp"

namespace slamer {

// Index of the first rule matching an object's features, -1 if none.
int matching_rule(LineKind kind, double coverage, double length, const RecognizerOptions& options);

// Probabilities over options.classes from the first rule matching the object
// (kind, coverage, length); they sum to 1. No matching rule: uniform.
std::vector<float> classify(LineKind kind, double coverage, double length, const RecognizerOptions& options);

// An object with the features the rules look at (coverage 0 for spatial lines).
struct RecognizedLine {
  LineObject object;
  double coverage = 0.0;
};

class LineRecognizer {
 public:
  explicit LineRecognizer(RecognizerOptions options) : options_(std::move(options)) {}

  LineObjectSet recognize(const LaserScan& scan) const;
  // The same, with each object's features (for calibrating the rules).
  std::vector<RecognizedLine> recognize_with_features(const LaserScan& scan) const;
  const RecognizerOptions& options() const { return options_; }

 private:
  RecognizerOptions options_;
};

}  // namespace slamer

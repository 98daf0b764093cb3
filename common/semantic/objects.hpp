// Environment-recognition results as the libraries see them: line objects
// in the sensor frame with class probabilities (the paper's c-hat, from the
// recognizer) and their counterparts in the map frame with posteriors (from
// SLAMER). The class list is data: it travels with every result.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace slamer {

enum class LineKind : int8_t { kPhysical = 0, kSpatial = 1 };

struct LineObject {
  LineKind kind = LineKind::kPhysical;
  Eigen::Vector2d start{0.0, 0.0};  // sensor frame [m] (map frame in SemanticObjects)
  Eigen::Vector2d end{0.0, 0.0};
  int npoints = 0;
  std::vector<float> probs;  // one per class, sums to 1
  int label = -1;            // most likely class (SemanticObjects), -1 if undecided
};

struct LineObjectSet {
  int64_t utime = 0;  // the scan's
  int64_t seq = 0;
  std::vector<std::string> class_names;
  std::vector<LineObject> objects;
};

// Index of the largest probability, -1 for an empty list.
int most_likely(const std::vector<float>& probs);

// The recognition classes of the paper's indoor case (Sec. VI-B): what the
// recognizer emits by default and what the localizer's class_map expects.
std::vector<std::string> paper_recognition_classes();

}  // namespace slamer

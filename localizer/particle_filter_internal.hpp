// What the ParticleFilter's source files share and nothing else sees: a
// scan and its objects prepared once per update for every particle's
// likelihood, and the constants of the scan-fit status and the proposals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "localizer/particle_filter.hpp"

namespace slamer {

struct ParticleFilter::PreparedScan {
  ScanPoints points;  // used beams' end points in the sensor frame, in cells
  // SLFM: the points of each class field (index = field); a beam of an unknown
  // class is in none (pose-independent).
  std::vector<ScanPoints> by_field;
};

struct ParticleFilter::PreparedObjects {
  // FNV-1a over the cells' coordinates.
  struct CellsHash {
    std::size_t operator()(const std::vector<int32_t>& cells) const {
      uint64_t h = 14695981039346656037ull;
      for (const int32_t v : cells) {
        h = (h ^ static_cast<uint32_t>(v)) * 1099511628211ull;
      }
      return static_cast<std::size_t>(h);
    }
  };
  struct Object {
    LineObject object;
    std::vector<Eigen::Vector2d> samples;  // sensor frame [m]
    std::vector<double> log_recognition;   // per recognition class: log Dir(c-hat; a(l))
    std::vector<int> field;                // per recognition class: map class, -1 free space, -2 none
    // objects_weight's term of this object by the cells its samples fall in
    // (x, y per sample; off the map -1, -1): the term depends on nothing
    // else, so particles that put every sample in the same cells, as most of
    // a tracked cloud does, share one computation (the same bits). Filled
    // while the prepared objects are used: a memo, not a result.
    mutable std::unordered_map<std::vector<int32_t>, double, CellsHash> weight_by_cells;
  };
  std::vector<Object> objects;
  std::vector<std::string> class_names;
  std::vector<double> training_prior;  // pi^e per class (empty: none)
};

namespace filter_constants {
inline constexpr double kFitSmoothing = 0.1;  // per scan: about 10 scans (0.25 s at 40 Hz)
inline constexpr int kProposalBeams = 48;     // beams a global proposal is scored with
}  // namespace filter_constants

}  // namespace slamer

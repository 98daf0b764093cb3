// The likelihood field of the LFM measurement model (paper Eqs. (10)-(13),
// Thrun et al., Probabilistic Robotics 6.4) in log space:
//   p(end point in cell) = z_hit * N(d; 0, sigma_hit^2) + z_rand / range_max
// with d the distance from the cell to the nearest obstacle. A beam at
// range_max scores z_max + z_rand / range_max; an end point off the map
// scores z_rand / range_max (nothing is known there).
//
// The distances come quantized (DistanceField), so the log-likelihood is one
// table entry per distance level; the field itself holds no grid and can
// share its distances with other users (SLFM's per-class fields share the
// SLAMER prior's).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "common/map/distance_field.hpp"

namespace slamer {

struct LikelihoodFieldOptions {
  double sigma_hit = 0.2;  // [m]
  double z_hit = 0.9;
  double z_max = 0.05;
  double z_rand = 0.05;
  double range_max = 30.0;  // [m]
  bool operator==(const LikelihoodFieldOptions&) const = default;
};

// The distance beyond which the hit term is below 1e-4 of the random term, so
// treating it as zero changes a log-likelihood by less than 1e-4: how far a
// distance field for this model must reach. Throws like LikelihoodField.
double likelihood_field_reach(const LikelihoodFieldOptions& options);

// term(0) + ... + term(n - 1) in four running sums: with one, every term
// would wait for the previous addition (a chain of 4-cycle latencies longer
// than a field lookup). The terms are floats, so the double sums are nearly
// always exact and the order does not change the result.
template <class Term>
double sum_terms(std::size_t n, const Term& term) {
  double sums[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    sums[0] += term(i);
    sums[1] += term(i + 1);
    sums[2] += term(i + 2);
    sums[3] += term(i + 3);
  }
  for (; i < n; ++i) {
    sums[0] += term(i);
  }
  return (sums[0] + sums[1]) + (sums[2] + sums[3]);
}

class LikelihoodField {
 public:
  // Throws std::invalid_argument unless sigma_hit, range_max > 0, the weights
  // are non-negative and sum to 1, and the distances reach likelihood_field_reach().
  // With dense_cells_max > 0 and a map of at most that many cells, the field
  // also keeps the levels row-major, a byte a cell and one saturated cell
  // past the last for off the map: sum_placed then reads a cell with one
  // load instead of two (the tile, then the cell), 20 % of the localizer's
  // time on fr079, and an off-map point with no branch.
  // kBest sums a dense field with AVX2 where the machine has it
  // (placed_keys_avx2.hpp), to the bit as kPortable does.
  enum class Vectorization { kBest, kPortable };
  LikelihoodField(std::shared_ptr<const DistanceField> obstacles, const LikelihoodFieldOptions& options,
                  std::size_t dense_cells_max = 0, Vectorization vectorization = Vectorization::kBest);

  const GridGeometry& geometry() const { return distances_->geometry(); }
  const DistanceField& distances() const { return *distances_; }
  float log_likelihood(int x, int y) const { return table_[distances_->level(x, y)]; }
  // The lookup by grid coordinates, by value for hot loops (see DistanceField::Levels).
  struct Cells {
    DistanceField::Levels levels;
    const float* table;
    float off_map;
    float width, height;  // [cells]
    // Log-likelihood of an end point at (gx, gy) [cells from the grid's origin].
    float operator()(float gx, float gy) const {
      return gx >= 0.0f && gy >= 0.0f && gx < width && gy < height
                 ? table[levels(static_cast<int>(gx), static_cast<int>(gy))]
                 : off_map;
    }
  };
  // Sum of the log-likelihoods of the n end points (x[i], y[i]) [cells, sensor
  // frame] placed on the grid by the rotation (c, s) = (cos, sin) and the
  // translation (tx, ty) [cells]: the same as summing cells()(c x - s y + tx,
  // s x + c y + ty), four points at a time where it is one lookup each.
  double sum_placed(const float* x, const float* y, std::size_t n, float c, float s, float tx, float ty) const;
  // A scan placed on the grid once, in whole cells, to be summed at many
  // whole-cell shifts: the inner loop of a correlative search (Olson,
  // "Real-time correlative scan matching", ICRA 2009), where a heading's
  // points are rotated once and each translation of the search's grid only
  // moves them by whole cells.
  struct CellScan {
    std::vector<int32_t> x, y;  // [cells] each point's cell (clamped to +-2^24 far off the grid)
    // y * width + x per point where the field is dense and every one is an int32; empty otherwise.
    std::vector<int32_t> keys;
    int32_t min_x = 0, max_x = -1, min_y = 0, max_y = -1;  // the cells' bounds (empty: max < min)
  };
  // The cells of the n points (x[i], y[i]) [cells, sensor frame] placed on the
  // grid by the rotation (c, s) and the translation (tx, ty) [cells], as
  // sum_placed places them (a NaN point falls off the grid).
  CellScan place_cells(const float* x, const float* y, std::size_t n, float c, float s, float tx, float ty) const;
  // Sum of the log-likelihoods of the cells of `scan` moved by (dx, dy)
  // [cells]: sum_placed of the same points translated by (tx + dx, ty + dy)
  // but for a point within a float's rounding of a cell's edge. Where the
  // moved scan lies wholly on a dense grid, a lookup per point and no checks.
  double sum_shifted(const CellScan& scan, int32_t dx, int32_t dy) const;
  Cells cells() const {
    return {distances_->levels(), table_.data(), off_map_, static_cast<float>(geometry().width),
            static_cast<float>(geometry().height)};
  }
  float log_likelihood_at(const Eigen::Vector2d& world) const;
  float off_map_log_likelihood() const { return off_map_; }
  float max_range_log_likelihood() const { return max_range_; }
  std::size_t dense_bytes() const { return dense_levels_ ? dense_levels_->size() : 0; }  // cells + 1
  bool sums_with_avx2() const { return avx2_ && dense_levels_ != nullptr; }

 private:
  std::shared_ptr<const DistanceField> distances_;
  std::array<float, DistanceField::kSaturated + 1> table_{};        // per distance level
  std::array<double, DistanceField::kSaturated + 1> table_wide_{};  // the same, widened once, not per beam
  float off_map_ = 0.0f;
  float max_range_ = 0.0f;
  // Row-major, or null; shared, so copies of the field share it as they share the distances.
  std::shared_ptr<const std::vector<uint8_t>> dense_levels_;
  bool avx2_ = false;
};

}  // namespace slamer

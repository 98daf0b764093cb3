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

class LikelihoodField {
 public:
  // Throws std::invalid_argument unless sigma_hit, range_max > 0, the weights
  // are non-negative and sum to 1, and the distances reach likelihood_field_reach().
  LikelihoodField(std::shared_ptr<const DistanceField> obstacles, const LikelihoodFieldOptions& options);

  const GridGeometry& geometry() const { return distances_->geometry(); }
  const DistanceField& distances() const { return *distances_; }
  float log_likelihood(int x, int y) const { return table_[distances_->level(x, y)]; }
  float log_likelihood_at(const Eigen::Vector2d& world) const;
  float off_map_log_likelihood() const { return off_map_; }
  float max_range_log_likelihood() const { return max_range_; }

 private:
  std::shared_ptr<const DistanceField> distances_;
  std::array<float, DistanceField::kSaturated + 1> table_{};  // per distance level
  float off_map_ = 0.0f;
  float max_range_ = 0.0f;
};

}  // namespace slamer

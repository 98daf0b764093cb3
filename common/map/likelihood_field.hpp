// The likelihood field of the LFM measurement model (paper Eqs. (10)-(13),
// Thrun et al., Probabilistic Robotics 6.4), precomputed per cell in log space:
//   p(end point in cell) = z_hit * N(d; 0, sigma_hit^2) + z_rand / range_max
// with d the distance from the cell to the nearest obstacle. A beam at
// range_max scores z_max + z_rand / range_max; an end point off the map
// scores z_rand / range_max (nothing is known there).
#pragma once

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
};

class LikelihoodField {
 public:
  // Throws std::invalid_argument unless sigma_hit, range_max > 0, the weights
  // are non-negative and sum to 1.
  LikelihoodField(const DistanceField& obstacles, const LikelihoodFieldOptions& options);

  const GridGeometry& geometry() const { return geometry_; }
  float log_likelihood(int x, int y) const { return log_likelihood_[geometry_.index(x, y)]; }
  float log_likelihood_at(const Eigen::Vector2d& world) const;
  float off_map_log_likelihood() const { return off_map_; }
  float max_range_log_likelihood() const { return max_range_; }

 private:
  GridGeometry geometry_;
  std::vector<float> log_likelihood_;
  float off_map_ = 0.0f;
  float max_range_ = 0.0f;
};

}  // namespace slamer

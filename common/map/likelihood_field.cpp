#include "common/map/likelihood_field.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace slamer {

LikelihoodField::LikelihoodField(const DistanceField& obstacles, const LikelihoodFieldOptions& options)
    : geometry_(obstacles.geometry()), log_likelihood_(geometry_.size()) {
  const double weights = options.z_hit + options.z_max + options.z_rand;
  if (!(options.sigma_hit > 0.0) || !(options.range_max > 0.0) || options.z_hit < 0.0 || options.z_max < 0.0 ||
      options.z_rand < 0.0 || std::abs(weights - 1.0) > 1e-6) {
    throw std::invalid_argument("likelihood field: need sigma_hit > 0, range_max > 0, z_hit + z_max + z_rand = 1");
  }
  const double random = options.z_rand / options.range_max;
  const double normalizer = options.z_hit / (std::sqrt(2.0 * std::numbers::pi) * options.sigma_hit);
  const double inv_two_var = 1.0 / (2.0 * options.sigma_hit * options.sigma_hit);
  for (int y = 0; y < geometry_.height; ++y) {
    for (int x = 0; x < geometry_.width; ++x) {
      const double d = obstacles.at(x, y);
      const double hit = std::isfinite(d) ? normalizer * std::exp(-d * d * inv_two_var) : 0.0;
      log_likelihood_[geometry_.index(x, y)] = static_cast<float>(std::log(hit + random));
    }
  }
  off_map_ = static_cast<float>(std::log(random));
  max_range_ = static_cast<float>(std::log(options.z_max + random));
}

float LikelihoodField::log_likelihood_at(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = geometry_.cell_at(world);
  return cell ? log_likelihood(cell->x, cell->y) : off_map_;
}

}  // namespace slamer

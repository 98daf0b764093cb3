#include "common/map/likelihood_field.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace slamer {
namespace {

void check(const LikelihoodFieldOptions& options) {
  const double weights = options.z_hit + options.z_max + options.z_rand;
  if (!(options.sigma_hit > 0.0) || !(options.range_max > 0.0) || !(options.z_rand > 0.0) || options.z_hit < 0.0 ||
      options.z_max < 0.0 || !(std::abs(weights - 1.0) <= 1e-6)) {
    throw std::invalid_argument(
        "likelihood field: need sigma_hit > 0, range_max > 0, z_rand > 0, z_hit + z_max + z_rand = 1");
  }
}

double hit_normalizer(const LikelihoodFieldOptions& options) {
  return options.z_hit / (std::sqrt(2.0 * std::numbers::pi) * options.sigma_hit);
}

}  // namespace

double likelihood_field_reach(const LikelihoodFieldOptions& options) {
  check(options);
  const double random = options.z_rand / options.range_max;
  const double ratio = hit_normalizer(options) / (1e-4 * random);
  return ratio > 1.0 ? options.sigma_hit * std::sqrt(2.0 * std::log(ratio)) : options.sigma_hit;
}

LikelihoodField::LikelihoodField(std::shared_ptr<const DistanceField> obstacles, const LikelihoodFieldOptions& options)
    : distances_(std::move(obstacles)) {
  const double reach = likelihood_field_reach(options);
  if (distances_ == nullptr || distances_->max_distance() < reach) {
    throw std::invalid_argument("likelihood field: distances must reach " + std::to_string(reach) + " m");
  }
  const double random = options.z_rand / options.range_max;
  const double normalizer = hit_normalizer(options);
  const double inv_two_var = 1.0 / (2.0 * options.sigma_hit * options.sigma_hit);
  for (int level = 0; level <= DistanceField::kSaturated; ++level) {
    const double d = level * distances_->step();
    const double hit = level < DistanceField::kSaturated ? normalizer * std::exp(-d * d * inv_two_var) : 0.0;
    table_[static_cast<std::size_t>(level)] = static_cast<float>(std::log(hit + random));
  }
  off_map_ = static_cast<float>(std::log(random));
  max_range_ = static_cast<float>(std::log(options.z_max + random));
}

float LikelihoodField::log_likelihood_at(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = geometry().cell_at(world);
  return cell ? log_likelihood(cell->x, cell->y) : off_map_;
}

}  // namespace slamer

#include "localizer/global_proposals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slamer {

GlobalProposals::GlobalProposals(std::shared_ptr<const DistanceField> free_space,
                                 std::shared_ptr<const DistanceField> obstacles, double clearance)
    : geometry_(obstacles->geometry()),
      free_space_(std::move(free_space)),
      obstacles_(std::move(obstacles)),
      clearance_(clearance) {
  for (int y = 0; y < geometry_.height; ++y) {
    for (int x = 0; x < geometry_.width; ++x) {
      if (usable(x, y)) {
        ++free_cells_;
        x0_ = free_cells_ == 1 ? x : std::min(x0_, x);
        y0_ = free_cells_ == 1 ? y : y0_;
        x1_ = std::max(x1_, x);
        y1_ = y;
      }
    }
  }
}

bool GlobalProposals::usable(int x, int y) const {
  return free_space_->level(x, y) == 0 && obstacles_->at(x, y) >= clearance_;
}

Pose2 GlobalProposals::uniform(std::mt19937& rng) const {
  std::uniform_int_distribution<int> column(x0_, x1_);
  std::uniform_int_distribution<int> row(y0_, y1_);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int cx = x0_;
  int cy = y0_;
  // A free map has far more than 1/1000 of its bounding box usable; give up
  // (keeping the last try) rather than loop on a pathological map.
  for (int attempt = 0; attempt < 1000; ++attempt) {
    cx = column(rng);
    cy = row(rng);
    if (usable(cx, cy)) {
      break;
    }
  }
  // Anywhere inside the cell, in the map frame.
  // One draw a statement: a constructor's arguments are evaluated in no set order (GCC right to
  // left, clang left to right), so two draws in one call differ between compilers. y first is
  // the order every figure so far was measured with.
  const double within_y = unit(rng);
  const double within_x = unit(rng);
  const Eigen::Vector2d local((cx + within_x) * geometry_.resolution, (cy + within_y) * geometry_.resolution);
  const Eigen::Vector2d world = transform_point(geometry_.origin, local);
  return {world.x(), world.y(), wrap_angle((2.0 * unit(rng) - 1.0) * std::numbers::pi)};
}

std::vector<Pose2> GlobalProposals::propose(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                                            int candidates, int keep, int beams, std::mt19937& rng) const {
  if (free_cells_ == 0 || points.x.empty() || candidates < 1 || keep < 1) {
    return {};
  }
  const std::size_t step = std::max<std::size_t>(1, points.x.size() / static_cast<std::size_t>(std::max(beams, 1)));
  const ScanPoints thinned = thinned_points(points, step);
  std::vector<std::pair<double, Pose2>> scored;
  scored.reserve(static_cast<std::size_t>(candidates));
  for (int k = 0; k < candidates; ++k) {
    const Pose2 pose = uniform(rng);
    scored.emplace_back(field_log_likelihood(field, thinned, sensor_in_cells(geometry_, pose, mount)), pose);
  }
  const std::size_t n = std::min(scored.size(), static_cast<std::size_t>(keep));
  std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(n), scored.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Pose2> best;
  for (std::size_t i = 0; i < n; ++i) {
    best.push_back(scored[i].second);
  }
  return best;
}

}  // namespace slamer

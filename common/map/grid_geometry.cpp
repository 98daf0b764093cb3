#include "common/map/grid_geometry.hpp"

#include <cmath>

namespace slamer {

Eigen::Vector2d GridGeometry::to_grid(const Eigen::Vector2d& world) const {
  return transform_point(inverse(origin), world) / resolution;
}

std::optional<Cell> GridGeometry::cell_at(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d g = to_grid(world);
  if (!(g.x() >= 0.0 && g.y() >= 0.0 && g.x() < width && g.y() < height)) {  // also false for NaN
    return std::nullopt;
  }
  return Cell{static_cast<int>(g.x()), static_cast<int>(g.y())};
}

Eigen::Vector2d GridGeometry::cell_center(int x, int y) const {
  return transform_point(origin, Eigen::Vector2d((x + 0.5) * resolution, (y + 0.5) * resolution));
}

}  // namespace slamer

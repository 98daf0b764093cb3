#include "tools/annotate/object_cells.hpp"

#include <algorithm>
#include <cmath>

#include "common/geometry/polygon.hpp"
#include "common/geometry/se2.hpp"

namespace slamer {
namespace {

// Grid cells [x0, x1] x [y0, y1] around `points` (grid coordinates) grown by `margin` cells, clamped to the map.
struct CellBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};
CellBox box_around(const std::vector<Eigen::Vector2d>& points, double margin, const GridGeometry& geometry) {
  Eigen::Vector2d low = points.front();
  Eigen::Vector2d high = points.front();
  for (const Eigen::Vector2d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  CellBox box;
  box.x0 = std::max(0, static_cast<int>(std::floor(low.x() - margin)) - 1);
  box.y0 = std::max(0, static_cast<int>(std::floor(low.y() - margin)) - 1);
  box.x1 = std::min(geometry.width - 1, static_cast<int>(std::ceil(high.x() + margin)) + 1);
  box.y1 = std::min(geometry.height - 1, static_cast<int>(std::ceil(high.y() + margin)) + 1);
  return box;
}

}  // namespace

std::vector<std::size_t> object_cells(const MapObject& object, const GridGeometry& geometry) {
  std::vector<Eigen::Vector2d> grid;  // the points in cell units
  for (const Eigen::Vector2d& p : object.points) {
    grid.push_back(geometry.to_grid(p));
  }
  std::vector<std::size_t> cells;
  if (grid.empty()) {
    return cells;
  }
  const bool filled = object.shape == ObjectShape::kPolygon && !object.thickness;
  // Half the stroke in cells; a small tolerance so a centre exactly at the edge counts.
  const double half = std::max(object.thickness.value_or(0.0), geometry.resolution) / 2.0 / geometry.resolution + 1e-9;
  std::vector<Eigen::Vector2d> stroke = grid;
  if (object.shape == ObjectShape::kPolygon) {
    stroke.push_back(grid.front());  // the outline is closed
  }
  const CellBox box = box_around(grid, filled ? 0.0 : half, geometry);
  for (int y = box.y0; y <= box.y1; ++y) {
    for (int x = box.x0; x <= box.x1; ++x) {
      const Eigen::Vector2d centre(x + 0.5, y + 0.5);
      bool covered = false;
      if (filled) {
        covered = inside_polygon(centre, grid);
      } else {
        for (std::size_t i = 0; i + 1 < stroke.size() && !covered; ++i) {
          covered = distance_to_segment(centre, stroke[i], stroke[i + 1]) <= half;
        }
      }
      if (covered) {
        cells.push_back(geometry.index(x, y));
      }
    }
  }
  return cells;
}

}  // namespace slamer

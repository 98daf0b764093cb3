// Where the cells of a 2D grid map are in the world (ROS map_server
// convention): cell (0, 0) is the bottom-left pixel of the image, its corner
// is at `origin` (x, y, yaw), cells are `resolution` metres square. Image row
// r is grid row height - 1 - r.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>

#include "common/geometry/se2.hpp"

namespace slamer {

struct Cell {
  int x = 0;
  int y = 0;
  bool operator==(const Cell&) const = default;
};

struct GridGeometry {
  int width = 0;
  int height = 0;
  double resolution = 0.05;  // [m per cell]
  Pose2 origin;              // pose of the corner of cell (0, 0) in the world

  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
  // The cell containing a world point; nullopt off the map (or for NaN input).
  std::optional<Cell> cell_at(const Eigen::Vector2d& world) const;
  // Cell coordinates as real numbers (cell (i, j) spans [i, i+1) x [j, j+1)).
  Eigen::Vector2d to_grid(const Eigen::Vector2d& world) const;
  Eigen::Vector2d cell_center(int x, int y) const;
};

}  // namespace slamer

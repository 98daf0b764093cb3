// Exact Euclidean distance transform of a grid (Felzenszwalb & Huttenlocher,
// "Distance Transforms of Sampled Functions", 2012): for every cell, the
// distance in metres from its centre to the nearest centre of a target cell,
// in O(cells) by two passes of the 1D lower envelope of parabolas. Unlike the
// 3x3/5x5 chamfer masks, the result is exact at every distance.
//
// Used for the likelihood field of the LFM (paper Eqs. (10)-(11), distance to
// the nearest obstacle) and the per-class map prior of SLAMER (Eq. (7),
// distance to the nearest cell of class l).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "common/map/grid_geometry.hpp"

namespace slamer {

class DistanceField {
 public:
  DistanceField() = default;
  // `is_target` has geometry.size() entries, non-zero where the cell is a target.
  DistanceField(const GridGeometry& geometry, const std::vector<uint8_t>& is_target);

  const GridGeometry& geometry() const { return geometry_; }
  bool has_targets() const { return has_targets_; }
  // Distance [m] at a cell; +inf everywhere when there is no target.
  float at(int x, int y) const { return distance_[geometry_.index(x, y)]; }
  float at_index(std::size_t index) const { return distance_[index]; }
  // Distance [m] of the cell containing a world point; nullopt off the map.
  std::optional<float> at_world(const Eigen::Vector2d& world) const;

 private:
  GridGeometry geometry_;
  std::vector<float> distance_;
  bool has_targets_ = false;
};

}  // namespace slamer

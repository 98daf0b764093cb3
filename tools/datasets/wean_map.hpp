// The CMU 16-831 Wean Hall map (wean.dat, plain or gzip) as grid cells:
// header lines `robot_specifications->KEY VALUE` (resolution in cm), then
// `global_map[0]: W H`, then H rows of W numbers, each the probability that
// the cell is free (-1 unknown). File row i is grid row y = i (the origin at
// the lower left, as the course's map reader plots it), cell x = column.
// Occupied: P(free) <= 0.35 (P(occupied) >= 0.65, map_server's occupied
// threshold); free: P(free) >= 0.804 (P(occupied) <= 0.196); else unknown.
#pragma once

#include <string>
#include <vector>

#include "common/map/grid_geometry.hpp"
#include "common/map/semantic_map.hpp"

namespace slamer {

struct GridCells {
  GridGeometry geometry;
  std::vector<Occupancy> cells;
};

// Throws std::runtime_error ("FILE:LINE: reason") on a malformed file.
GridCells read_wean_map(const std::string& path);

}  // namespace slamer

// The CMU 16-831 Wean Hall map (wean.dat, plain or gzip) as grid cells:
// header lines `robot_specifications->KEY VALUE` (resolution in cm), then
// `global_map[0]: SIZE_Y SIZE_X`, then SIZE_X lines of SIZE_Y numbers, each
// the probability that the cell is free (-1 unknown): line i is the column
// x = i, its k-th number the cell y = k (the origin at the lower left). That
// is the order of the course's reader (bee-map.c: x outer, y inner) and the
// map so read is the handout's picture, wean.gif; read row by row instead it
// is that picture mirrored, which the scans fit only along symmetric corridors.
// The header's global_mapsize_x and _y (cm), where given, must agree with
// SIZE_X and SIZE_Y: they say which number is which.
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

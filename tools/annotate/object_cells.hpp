// Which cells of a grid an object of slamer-annotate-map covers
// (object_list.hpp). Works in grid coordinates, so a rotated map origin is
// handled like any other: a line covers every cell whose centre lies within
// half its thickness (at least half a cell) of the polyline, rounded ends as
// the bundled floor plans draw them (tools/sim/floor_plan.cpp); a filled
// polygon covers every cell whose centre lies inside it (even-odd rule); a
// polygon with a thickness is the closed line along its edges.
#pragma once

#include <cstddef>
#include <vector>

#include "common/map/grid_geometry.hpp"
#include "tools/annotate/object_list.hpp"

namespace slamer {

// Cell indices (GridGeometry::index), in increasing order, without repeats;
// cells off the map are left out.
std::vector<std::size_t> object_cells(const MapObject& object, const GridGeometry& geometry);

}  // namespace slamer

// The objects slamer-annotate-map paints onto a map_server map (issue 15,
// "Your own robot and map"): classed line segments and polygons in the map
// frame [m], read from a small YAML file:
//
//   classes:            # optional: classes beyond the map's and the project's
//     - {name: lift_door, color: [0, 128, 255]}
//   objects:            # painted in order, a later object over an earlier one
//     - {name: lab door, class: door, line: [3.5, 7.0, 4.5, 7.0], thickness: 0.1, occupancy: occupied}
//     - {class: fence, polygon: [9, 3, 15, 3, 15, 3.2, 9, 3.2]}
//
// An object is exactly one of `line` (a polyline, x0, y0, x1, y1, ...: at
// least 2 points) or `polygon` (at least 3 points; filled, or only its outline
// when `thickness` is given). `thickness` [m] is the stroke's full width
// (default and minimum: one cell). `occupancy` says what the painted cells
// become in the occupancy grid: `keep` (default: what the SLAM saw), `occupied`
// (e.g. a door to be known closed) or `free` (open). `name` is optional and
// appears in messages and on the preview.
//
// The class table of the result is the map's own (if it has one), then the
// project's classes it lacks (door, glass_door, fence, no_entry_line, others,
// in the paper's colours: the semantic map format of common/map/semantic_map.hpp),
// then the file's. Every problem is one ConfigError line naming the file, the
// line and the object: unknown class, too few points, a point outside the
// map, a number that is not one, a polygon covering no cell.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"

namespace slamer {

enum class ObjectShape { kLine, kPolygon };
enum class CellOccupancy { kKeep, kOccupied, kFree };

struct MapObject {
  std::string name;  // may be empty
  std::string class_name;
  ObjectShape shape = ObjectShape::kLine;
  std::vector<Eigen::Vector2d> points;  // map frame [m]
  std::optional<double> thickness;      // [m]; none: one cell (lines), filled (polygons)
  CellOccupancy occupancy = CellOccupancy::kKeep;
};

struct ObjectList {
  std::vector<SemanticClass> classes;  // the result's class table
  std::vector<MapObject> objects;
};

// door, glass_door, fence, no_entry_line, others, in the colours of the
// bundled maps (the paper's Fig. 3).
std::vector<SemanticClass> project_classes();

// Reads an objects file for `map` (its class table and extent) and checks
// every object; rejects unknown keys.
ObjectList read_object_list(const ConfigReader& reader, const SemanticMap& map);
ObjectList load_object_list(const std::string& path, const SemanticMap& map);

}  // namespace slamer

// A semantic map: the geometric occupancy grid in ROS map_server format
// (YAML + PGM/PNG) plus a per-cell class label from a lossless colour image
// of the same size and a class table (name, colour). Two files formats load:
//
//  * map_server YAML (image, resolution, origin [x, y, yaw], occupied_thresh,
//    free_thresh, negate, optional mode) with an optional `semantic:` section
//    { image, classes: [{name, color: [R, G, B]}], occupied_class }.
//  * the published SLAMER implementation's ism.yaml: image (the colour
//    layer), ogm_info_yaml (a map_server YAML beside it), objects: [names],
//    and <name>_color: [R, G, B] per object; (205,205,205) is unknown and
//    (254,254,254) free space. Its `do_not_enter_line` is this project's
//    `no_entry_line` and loads under that name (its colour is still read from
//    `do_not_enter_line_color`), so the localizer's class_map and the
//    evaluation see one name whichever format the map came in; a file
//    listing both is an error.
//
// Occupied cells with no class colour get `occupied_class` (default "others"
// when the table has it), so walls are a class like any other. Colours in
// no class are counted and reported, not guessed. Every problem with a file
// is a one-line ConfigError naming the file.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/config/config_reader.hpp"  // ConfigError
#include "common/map/distance_field.hpp"
#include "common/map/grid_geometry.hpp"

namespace slamer {

enum class Occupancy : uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct SemanticClass {
  std::string name;
  std::array<uint8_t, 3> rgb{};
};

struct SemanticMap {
  GridGeometry geometry;
  std::vector<Occupancy> occupancy;    // per cell, index = geometry.index(x, y)
  std::vector<SemanticClass> classes;  // may be empty (a purely geometric map)
  std::vector<int8_t> labels;          // per cell: class index, or -1
  int64_t unknown_color_cells = 0;     // semantic pixels whose colour is in no class
  std::vector<std::string> warnings;   // one line each, for the log

  int class_index(std::string_view name) const;  // -1 if absent
};

SemanticMap load_semantic_map(const std::string& yaml_path);

// Distance [m], up to max_distance, to the nearest occupied cell; to the
// nearest cell of each class (index-aligned with map.classes); to the nearest
// free cell of no class that lies more than `class_margin` from every cell of a
// class (0: any free cell of no class), or more than `class_margins[c]` from a
// cell of class c where that is given (index-aligned with map.classes, > 0).
DistanceField obstacle_distance_field(const SemanticMap& map, double max_distance);
std::vector<DistanceField> class_distance_fields(const SemanticMap& map, double max_distance);
DistanceField free_space_distance_field(const SemanticMap& map, double max_distance, double class_margin = 0.0,
                                        const std::vector<double>& class_margins = {});

}  // namespace slamer

// Renders a floor plan (walls, doors, glass doors, fences, no-entry lines as
// thick polylines, each with a class) into a semantic map: a map_server PGM,
// the semantic colour PNG and the YAML tying them together. The bundled maps
// in config/maps/ are made this way from their plan.yaml.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"

namespace slamer {

struct PlanClass {
  std::string name;
  std::array<uint8_t, 3> rgb{};
  bool occupied = true;  // drawn occupied in the occupancy image unless a shape says otherwise
};

struct PlanShape {
  std::string class_name;
  double width = 0.1;  // [m]
  bool occupied = true;
  std::vector<Eigen::Vector2d> points;  // a polyline
};

struct FloorPlan {
  double resolution = 0.05;
  Eigen::Vector2d size{10.0, 10.0};                         // [m]
  Eigen::Vector2d origin{0.0, 0.0};                         // world position of the image's bottom-left corner
  bool unknown_background = true;                           // outside free_areas is unknown (205) rather than free
  std::vector<std::array<double, 4>> free_areas;            // [x0, y0, x1, y1] rectangles of known free space
  std::vector<std::vector<Eigen::Vector2d>> free_polygons;  // more known free space, any shape
  std::vector<PlanClass> classes;
  std::vector<PlanShape> shapes;
};
void read_options(const ConfigReader& reader, FloorPlan* plan);

// Writes map.pgm, semantic.png and map.yaml into `directory`.
void write_floor_plan_map(const FloorPlan& plan, const std::string& directory);

}  // namespace slamer

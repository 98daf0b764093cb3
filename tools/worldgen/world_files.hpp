// Writes a generated building as the files the stack reads: the floor plan
// (plan.yaml) and the semantic map rendered from it (map.pgm, semantic.png,
// map.yaml), the world for slamer-sim and slamer-eval (world.yaml: route,
// materials, truth), a copy of the robot, and differences.yaml, the map/truth
// differences for the evaluation (read back with read_options below).
#pragma once

#include <string>
#include <vector>

#include "tools/worldgen/building.hpp"

namespace slamer {

// Throws std::runtime_error if a file cannot be written.
void write_world(const Building& building, const WorldGenOptions& options, uint64_t seed, const std::string& robot_file,
                 const std::string& directory);

struct MapDifferences {  // differences.yaml
  struct Door {
    std::string class_name;
    Eigen::Vector2d center{0.0, 0.0};
    double width = 0.0;
    bool framed = false, hinged = false, on_route = false;
    std::string map_state = "closed", truth_state = "closed";  // truth at time 0
    std::vector<std::pair<double, std::string>> changes;
    bool differs() const { return map_state != truth_state || !changes.empty(); }
  };
  int64_t seed = 0;
  double duration_estimate = 0.0;
  std::vector<Door> doors;
  int added = 0;    // objects in the truth only
  int removed = 0;  // objects in the map only
};
void read_options(const ConfigReader& reader, MapDifferences* differences);

}  // namespace slamer

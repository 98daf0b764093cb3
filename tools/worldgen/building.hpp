// A random semantic building for testing recognition on worlds it was not
// fitted on (issue 11): a corridor with rooms of varied sizes on both sides,
// walls at any angle (the whole building turned, corners cut diagonally),
// doors 0.7-1.8 m wide with or without frames (without: the leaf as thick as
// the wall, flush with it), hinged or sliding, glass doors, fences, no-entry
// lines of any length and furniture. The map the robot is given differs from
// the truth: doors opened, closed or changing during the run, objects added
// and removed. The route visits some rooms and crosses no closed object.
// Deterministic for a seed (std::mt19937 only).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "tools/sim/world.hpp"

namespace slamer {

struct WorldGenOptions {
  struct Corridor {
    double length_min = 18.0, length_max = 34.0;  // [m]
    double width_min = 2.0, width_max = 3.2;      // [m]
    double end_glass_door_probability = 0.5;      // per corridor end
    double no_entry_probability = 0.6;            // a no-entry line across the corridor near its east end
  } corridor;
  struct Rooms {
    double width_min = 3.0, width_max = 8.0;  // [m] along the corridor
    double depth_min = 3.5, depth_max = 7.5;  // [m]
    double wall_min = 0.15, wall_max = 0.3;   // [m] wall thickness of the building
    double chamfer_probability = 0.35;        // a corner cut by a diagonal wall
    int furniture_max = 3;
    double fence_probability = 0.4;
    double no_entry_probability = 0.3;
  } rooms;
  struct Doors {
    double width_min = 0.7, width_max = 1.8;  // [m]
    double frame_probability = 0.5;           // jambs and a recessed leaf; else the leaf flush with the wall
    double glass_probability = 0.2;
    double hinged_probability = 0.5;  // an open hinged leaf stands in the room; a sliding one is gone
    double closed_in_map_probability = 0.5;
  } doors;
  struct Differences {
    double flip_probability = 0.3;                           // a door off the route in the other state than the map's
    double change_probability = 0.2;                         // a door off the route that changes during the run
    int corridor_objects_min = 1, corridor_objects_max = 2;  // cabinets the map does not have
    double room_object_probability = 0.5;                    // furniture the map does not have
    double removed_probability = 0.7;                        // furniture the map has and the truth not
  } differences;
  struct Route {
    int rooms_min = 2, rooms_max = 4;  // rooms entered (as many as there are, if fewer)
    double speed = 0.6;                // [m/s]
    double corridor_fraction = 1.0;    // how far along the corridor it drives, in (0, 1]
    bool return_to_start = false;
  } route;
  double rotation_probability = 0.7;  // the building turned by a random angle, else axis-aligned
  double resolution = 0.05;           // [m] of the map
};
void read_options(const ConfigReader& reader, WorldGenOptions* options);

struct BuildingShape {  // a thick segment of one class, as in a floor plan
  std::string class_name;
  Eigen::Vector2d a{0.0, 0.0}, b{0.0, 0.0};
  double width = 0.1;
  bool occupied = true;
};

struct BuildingDoor {
  std::string class_name;  // door or glass_door
  Eigen::Vector2d a{0.0, 0.0}, b{0.0, 0.0};
  double thickness = 0.1;
  bool framed = false;
  bool hinged = false;
  bool on_route = false;
  DoorState map_state = DoorState::kClosed;
  DoorState truth_state = DoorState::kClosed;         // at time 0
  std::vector<std::pair<double, DoorState>> changes;  // during the run
};

struct Building {
  std::vector<BuildingShape> shapes;  // what the map shows, doors aside
  std::vector<BuildingDoor> doors;
  std::vector<TruthObject> added;                       // in the truth only
  std::vector<TruthArea> removed;                       // in the map only (also in `shapes`)
  std::vector<std::vector<Eigen::Vector2d>> footprint;  // the building's known free space
  Pose2 start;
  std::vector<PathStep> path;
  double duration_estimate = 0.0;  // [s] of the route
  std::map<std::string, double> return_probability;
  std::map<std::string, double> reflectance;
};

Building generate_building(const WorldGenOptions& options, uint64_t seed);

}  // namespace slamer

// The simulated world: the semantic map the robot is given, plus the true
// world, which may differ from it (the mapping uncertainty SLAMER is about):
// a door the map shows closed is open, a door opens or closes at a given
// time, an object stands where the map has none.
//
// The true world is the map's grid with each cell's LiDAR behaviour taken
// from its class: a beam entering an object of class c comes back with
// probability return_probability[c] (walls 1, glass doors and fences a
// fraction, no-entry lines 0), drawn once per object crossed, not per cell.
// Cells of a door class belong to a door instance (a connected component);
// an open door returns nothing. Unlabelled occupied cells always return.
// A truth area (`truth.removed`) clears the map's cells under it: an object
// the map shows that is no longer there. With `reflectance` set, a beam that
// returns also carries the reflectance of the class it hit (intensities).
#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"
#include "common/robot/robot_options.hpp"

namespace slamer {

enum class DoorState { kOpen, kClosed };

struct DoorTruth {
  Eigen::Vector2d near{0.0, 0.0};                     // a point within snap_distance of the door
  std::optional<DoorState> state;                     // at time 0; absent = as the map shows it
  std::vector<std::pair<double, DoorState>> changes;  // (time [s], new state), ascending
};

struct TruthObject {  // an object of the true world that the map does not have
  std::string class_name;
  Eigen::Vector2d from{0.0, 0.0};
  Eigen::Vector2d to{0.0, 0.0};
  double thickness = 0.1;  // [m]
};

struct TruthArea {  // a stretch of the map that the true world does not have (an object removed)
  Eigen::Vector2d from{0.0, 0.0};
  Eigen::Vector2d to{0.0, 0.0};
  double thickness = 0.1;  // [m]
};

// Laser intensity of a return: scale * reflectance / (1 + range / falloff),
// times (1 + noise * N(0, 1)); device units like the URG's.
struct IntensityModel {
  double scale = 10000.0;
  double falloff = 5.0;  // [m]
  double noise = 0.02;
};

struct PathStep {
  enum class Kind { kGoTo, kTurnTo, kWait };
  Kind kind = Kind::kGoTo;
  Eigen::Vector2d target{0.0, 0.0};  // kGoTo
  double speed = 0.5;                // kGoTo [m/s]
  double heading = 0.0;              // kTurnTo [rad]
  double duration = 0.0;             // kWait [s]
};

struct WorldOptions {
  std::string map_path;    // semantic map YAML, resolved against the world file
  std::string robot_path;  // robot YAML, resolved against the world file
  Pose2 start;
  std::vector<PathStep> path;
  std::vector<std::string> door_classes{"door", "glass_door"};
  std::map<std::string, double> return_probability{
      {"door", 1.0}, {"glass_door", 0.3}, {"fence", 0.4}, {"no_entry_line", 0.0}, {"others", 1.0}};
  double door_snap_distance = 0.5;  // [m]
  std::vector<DoorTruth> doors;
  std::vector<TruthObject> objects;
  std::vector<TruthArea> removed;
  // Per class (unlabelled occupied cells: "others"); empty = no intensities.
  std::map<std::string, double> reflectance;
  IntensityModel intensity;
};
void read_options(const ConfigReader& reader, WorldOptions* options);

// What the simulator needs to know of the world, built once.
class TrueWorld {
 public:
  // Throws ConfigError (naming the world file) when a door or object does
  // not fit the map (no door near a point, a class the map does not have).
  TrueWorld(SemanticMap map, const WorldOptions& options, const std::string& world_file);

  const SemanticMap& map() const { return map_; }
  int door_count() const { return static_cast<int>(door_truth_.size()); }
  DoorState door_state(int door, double time) const;
  // The door a world point belongs to (-1 if none).
  int door_at(const Eigen::Vector2d& world) const;

  // Range [m] along a ray from `origin` with direction `angle`, up to
  // max_range; +inf when nothing returns. `rng` draws the partial returns.
  // `reflectance` (if given) receives the reflectance of what returned.
  double cast(const Eigen::Vector2d& origin, double angle, double max_range, double time, std::mt19937& rng,
              float* reflectance = nullptr) const;
  bool has_intensities() const { return !reflectance_.empty(); }

  // The true class of the world at a point (for evaluation): the class of
  // the nearest labelled cell within `radius`, -1 if none; `door` (if given)
  // receives that cell's door instance or -1.
  int class_near(const Eigen::Vector2d& world, double radius, int* door = nullptr) const;

 private:
  SemanticMap map_;
  std::vector<float> return_probability_;  // per cell, for non-door cells
  std::vector<int32_t> door_of_cell_;      // per cell, -1 if not a door
  std::vector<float> door_return_;         // per door instance, when closed
  std::vector<DoorTruth> door_truth_;      // per door instance, state always set
  std::vector<int32_t> object_of_cell_;    // per cell: an id for "same object" (class or door run)
  std::vector<int8_t> truth_labels_;       // map labels plus the truth objects
  std::vector<float> reflectance_;         // per cell; empty without intensities
};

}  // namespace slamer

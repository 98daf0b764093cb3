// The small room world of the localizer tests: its map, robot, and a scan
// simulated at a pose.
#pragma once

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "common/map/semantic_map.hpp"
#include "common/robot/robot_options.hpp"
#include "common/sensors/laser_scan.hpp"
#include "localizer/scan_fit.hpp"
#include "tools/sim/world.hpp"

namespace slamer {

// The scan `robot`'s lidar takes in `world` from `pose` (noise-free ranges up to 30 m).
inline LaserScan simulated_scan(const TrueWorld& world, const RobotOptions& robot, const Pose2& pose) {
  LaserScan scan;
  scan.angle_min = robot.lidar.angle_min;
  scan.angle_increment = robot.lidar.angle_increment();
  scan.range_min = static_cast<float>(robot.lidar.range_min);
  scan.range_max = static_cast<float>(robot.lidar.range_max);
  std::mt19937 rng(4);
  const Pose2 sensor = compose(pose, robot.lidar.mount);
  for (int i = 0; i < robot.lidar.beams; ++i) {
    const double r =
        world.cast({sensor.x, sensor.y}, sensor.theta + scan.angle(static_cast<std::size_t>(i)), 31.0, 0.0, rng);
    scan.ranges.push_back(r <= 30.0 ? static_cast<float>(r) : std::numeric_limits<float>::infinity());
  }
  return scan;
}

struct SmallWorld {
  WorldOptions options = load_options<WorldOptions>(std::string(SLAMER_SOURCE_DIR "/config/worlds/small_room.yaml"));
  RobotOptions robot = load_options<RobotOptions>(options.robot_path);
  SemanticMap map = load_semantic_map(options.map_path);
  TrueWorld world{map, options, "small_room"};

  LaserScan scan_at(const Pose2& pose) const { return simulated_scan(world, robot, pose); }
};

// A map at 5 cm of `width` x `height` cells with no classes, occupied where `occupied(x, y)`.
template <typename Occupied>
SemanticMap grid_map(int width, int height, Occupied occupied) {
  SemanticMap map;
  map.geometry.width = width;
  map.geometry.height = height;
  map.geometry.resolution = 0.05;
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      map.occupancy[map.geometry.index(x, y)] = occupied(x, y) ? Occupancy::kOccupied : Occupancy::kFree;
    }
  }
  return map;
}

// A scan's returns (not max range) as end points in the sensor frame, in cells of `resolution`.
inline ScanPoints end_points(const LaserScan& scan, double resolution) {
  ScanPoints points;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (scan.ranges[i] < scan.range_max) {
      const double r = scan.ranges[i] / resolution;
      points.x.push_back(static_cast<float>(r * std::cos(scan.angle(i))));
      points.y.push_back(static_cast<float>(r * std::sin(scan.angle(i))));
    }
  }
  return points;
}

}  // namespace slamer

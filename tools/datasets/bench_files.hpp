// slamer-bench's files around the localizer run: the robot YAML of a
// dataset (the laser where the log puts it, its beam geometry), the
// localizer config with the bench's particles, beam step, map and robot, and
// the POSE reports read back from the localizer's output log.
#pragma once

#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/sensors/laser_scan.hpp"
#include "tools/datasets/bench_scoring.hpp"
#include "tools/datasets/dataset_import.hpp"

namespace slamer {

// A robot file (config/robots format) for a log's laser: base defaults, lidar from the scan.
std::string dataset_robot_yaml(const std::string& name, const LaserScan& scan, const Pose2& mount);

struct BenchConfigChanges {
  int particles = 500;
  int beam_step = 1;
  std::string map;  // absolute paths
  std::string robot;
};
// The YAML of `base_config` with the changes applied (localizer.particles,
// localizer.lfm.beam_step, map, robot). Throws ConfigError if it cannot be read.
std::string bench_localizer_config(const std::string& base_config, const BenchConfigChanges& changes);

// The log up to its first scan (with its reference and odometry): a localizer
// run on it measures what starting up costs, to take out of the time per scan.
ImportedLog first_scan_only(const ImportedLog& log);

// Writes `text` to `path`; throws std::runtime_error if it cannot.
void write_text_file(const std::string& path, const std::string& text);

// Every decodable pose_estimate_t on `channel`; throws std::runtime_error if the log cannot be read.
std::vector<PoseReport> read_pose_reports(const std::string& lcm_path, const std::string& channel);

}  // namespace slamer

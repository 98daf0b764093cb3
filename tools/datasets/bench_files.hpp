// slamer-bench's files around the localizer run: the robot YAML of a
// dataset (the laser where the log puts it, its beam geometry), the
// localizer config with the bench's particles, beam step, map and robot, and
// the POSE reports read back from the localizer's output log.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
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

// The robot carried off unseen (the kidnapped robot): scans [from, to) and
// their reference are left out, and every later message comes earlier by
// scans[to].utime - scans[from].utime, so scan `to` follows scan from - 1 a
// scan period later; the odometry after it is re-anchored so that it measures
// the ordinary step from scan from - 1 to scan from across the carry (and
// nothing of the carry itself). Scans keep the log's own time (sensor_utime)
// and are renumbered. Needs 0 < from < to < scans and the rebuilt odometry at
// every scan (a corrected log); throws std::invalid_argument otherwise.
// Wheel ticks are not carried over (no CARMEN log has them).
ImportedLog kidnapped(const ImportedLog& log, std::size_t from, std::size_t to);

// slamer-localizer's arguments for a bench run: --config, --map, --robot, then --initial-pose X Y
// THETA (or --global without a start), --mode, --seed, --replay IN and --out OUT.
struct BenchLocalizerRun {
  std::string config;
  std::string map;
  std::string robot;
  std::string mode;
  std::string seed;
  std::optional<Pose2> start;  // none: global localization
};
std::vector<std::string> bench_localizer_args(const BenchLocalizerRun& run, const std::string& in,
                                              const std::string& out);

// The --kidnap values as scans [first, second) of a log of `scans` scans: whole numbers,
// 0 < FROM < TO < scans; throws CommandLineError otherwise.
std::pair<std::size_t, std::size_t> kidnap_scans(const std::vector<double>& values, std::size_t scans);

// One pose per scan of `log` (poses_per_scan with its scans' utimes and own times).
std::vector<BenchPose> poses_per_scan(const ImportedLog& log, const std::vector<PoseReport>& reports,
                                      const Pose2& initial_pose, int64_t* missing);

// poses.txt's poses for the whole log of a kidnapped run: `kept` (one per scan
// of the kidnapped log) with, for each scan carried unseen, [from, to), its own
// time and the pose and status of scan from - 1 (the localizer saw nothing
// since), has_report false. Throws std::invalid_argument unless kept has one
// pose per scan of the whole log but the carried ones and 0 < from < to.
std::vector<BenchPose> with_carried_scans(const std::vector<BenchPose>& kept, const ImportedLog& whole,
                                          std::size_t from, std::size_t to);

// "kidnap: scans FROM-TO-1 left out; at scan FROM (T s into the run) the robot was carried D m and
// A deg unseen", from the whole log's reference and the kidnapped log's time.
std::string describe_kidnap(const ImportedLog& whole, const ImportedLog& kidnapped_log, std::size_t from);

// Writes `text` to `path`; throws std::runtime_error if it cannot.
void write_text_file(const std::string& path, const std::string& text);

// Every decodable pose_estimate_t on `channel`; throws std::runtime_error if the log cannot be read.
std::vector<PoseReport> read_pose_reports(const std::string& lcm_path, const std::string& channel);

}  // namespace slamer

// Turns a dataset file into the streams the stack's LCM log carries: LIDAR
// scans, an ODOMETRY stream, WHEEL_ENCODERS (Mines) and GROUND_TRUTH (the
// corrected CARMEN logs' reference poses). Formats: dataset_records.hpp.
//
// Corrected CARMEN logs (GMapping output): each scan's pose is the corrected
// one and the ODOM lines are re-anchored to it after every scan, so the raw
// odometry increment from scan k to k+1 is inv(first ODOM after scan k) (+)
// (last ODOM before scan k+1). The raw stream is rebuilt by chaining these
// increments from the last ODOM before the first scan (the log's own odometry
// frame); every ODOM line between two scans becomes raw_k (+) inv(first ODOM
// after k) (+) ODOM. Such logs are recognized (auto) by the first ODOM after
// at least 90 % of the scans equalling the scan's pose with an earlier time
// (GMapping stamps it 0 or junk), or forced with `corrected`.
//
// Time: every message gets a strictly increasing `utime`, and a scan keeps
// the log's own time in `sensor_utime`.
//  * Scans of a corrected log: the log's time when it is at least 1 ms after
//    the previous scan's utime, else the previous utime + 100 ms (a nominal
//    scan period); a log where that is so for most scans has no time base
//    (csail prints its times with 6 digits: 365 equal, then a 10^4 s step)
//    and every scan goes at the nominal period.
//    The ODOM lines' times are not usable there (the re-anchoring line says
//    0), so the rebuilt pose at scan k is sent at scan k's utime, just before
//    the scan, and the poses between two scans are spread evenly between them.
//  * Everything else (raw CARMEN, CMU, Mines) in file order: the line's time
//    when it is later than the previous message's utime, else that + 1 ms.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/sensors/laser_scan.hpp"
#include "tools/datasets/dataset_records.hpp"

namespace slamer {

struct ImportOptions {
  enum class Corrected { kAuto, kYes, kNo };
  DatasetFormat format = DatasetFormat::kCarmen;
  Corrected corrected = Corrected::kAuto;
  std::size_t max_errors_kept = 10;  // malformed lines quoted in ImportedLog::errors (all are counted)
  // Mines base (SOURCE.txt): encoder ticks per wheel turn, wheel radius, half the axle [m].
  double mines_ticks_per_rev = 2000.0;
  double mines_wheel_radius = 0.077;
  double mines_half_axle = 0.165;
  Pose2 mines_laser_mount{0.145, 0.0, 0.0};
};

struct TimedPose {
  int64_t utime = 0;
  Pose2 pose;
  double v = 0.0;      // [m/s] from this pose and the previous one
  double omega = 0.0;  // [rad/s]
};

struct TickSample {
  int64_t utime = 0;
  int64_t left = 0;
  int64_t right = 0;
};

struct ImportedLog {
  std::vector<LaserScan> scans;      // utime strictly increasing; sensor_utime the log's own time; seq from 0
  std::vector<Pose2> reference;      // robot pose per scan (corrected logs), else empty
  std::vector<Pose2> scan_odometry;  // the (rebuilt) raw odometry pose at each scan, where known
  std::vector<TimedPose> odometry;   // the ODOMETRY stream, utime strictly increasing
  std::vector<TickSample> ticks;     // WHEEL_ENCODERS (Mines)
  std::optional<Pose2> laser_mount;  // the laser on the base, when the log states it
  bool corrected = false;
  int64_t lines = 0;
  int64_t malformed = 0;
  std::vector<std::string> errors;  // "FILE:LINE: reason" of the first malformed lines
  int64_t retimed = 0;              // messages whose log time did not advance
  int64_t reanchor_mismatches = 0;  // corrected: scans whose first ODOM after is not the scan's pose
  int64_t empty_intervals = 0;      // corrected: scans with no ODOM before the next (zero increment)
};

// Throws std::runtime_error if the file cannot be read.
ImportedLog import_dataset(const std::string& path, const ImportOptions& options);

// The messages of a log in the order to write them (utime, then odometry /
// encoders before the scan of the same time, ground truth after it).
enum class StreamKind { kOdometry, kTicks, kScan, kGroundTruth };
struct StreamEntry {
  StreamKind kind;
  std::size_t index;  // into the matching vector (kGroundTruth: into scans / reference)
  int64_t utime;
};
std::vector<StreamEntry> merge_streams(const ImportedLog& log);

// How dead reckoning on scan_odometry drifts from the reference (corrected logs).
struct OdometryDrift {
  double path_length = 0.0;             // [m] of the reference
  double heading_deg_per_m = 0.0;       // mean |heading error| gathered over 1 m of reference path
  double step_position_error = 0.0;     // mean |increment difference| per scan step [m]
  double step_heading_error_deg = 0.0;  // [deg]
  double final_position_error = 0.0;    // dead reckoning from the first reference pose [m]
  double max_position_error = 0.0;      // [m]
};
OdometryDrift odometry_drift(const ImportedLog& log);

}  // namespace slamer

// Every line type of the real 2D laser datasets in ../shared/datasets (see
// each SOURCE.txt), parsed into one record:
//  * CARMEN logs: `FLASER n r1..rn x y th odom_x odom_y odom_th ts host
//    logger_ts` (beams from -90 deg, 180 deg / n apart, 1 deg for n = 181
//    and 0.5 deg for 361 as GMapping's reader does; >= 49.99 m = no return),
//    `ROBOTLASER1 type start fov res max_range accuracy remission_mode n
//    r1..rn m e1..em laser_x laser_y laser_th robot_x robot_y robot_th tv rv
//    forward_safety side_safety turn_axis ts host logger_ts` (>= max_range =
//    no return) and `ODOM x y th tv rv accel ts host logger_ts`;
//  * CMU 16-831 Wean Hall logs (cm): `O x y th ts` and `L x y th xl yl thl
//    r1..r180 ts` (180 beams over 180 deg, 8183 cm and up = no return);
//  * Mines exp1.dat: `us ? left_ticks right_ticks <20 more> r1..r682 <last>`
//    (URG-04LX, 240 deg, mm, 0 = no return).
// Other lines (PARAM, NEFF, comments, blank) are ignored, never guessed at.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "common/geometry/se2.hpp"
#include "common/sensors/laser_scan.hpp"

namespace slamer {

enum class DatasetFormat { kCarmen, kCmu, kMines };

enum class RecordKind { kIgnored, kScan, kOdometry };

struct DatasetRecord {
  RecordKind kind = RecordKind::kIgnored;
  std::string tag;    // FLASER, ROBOTLASER1, ODOM, O, L; "" for Mines
  double time = 0.0;  // the log's own time of the line [s]
  LaserScan scan;     // kScan: utime = sensor_utime = time, seq 0
  // kScan: the sensor pose the line states (FLASER x y th, ROBOTLASER1
  // laser pose, CMU xl yl thl); kOdometry: the odometry pose. [m, rad]
  Pose2 pose;
  // kScan: the robot pose the line states (FLASER odom_*, ROBOTLASER1 robot
  // pose, CMU x y th); none for Mines.
  Pose2 base_pose;
  bool has_poses = false;
  double v = 0.0;  // kOdometry, CARMEN: translational and rotational speed [m/s, rad/s]
  double omega = 0.0;
  bool has_ticks = false;  // Mines: the wheel encoder counts of the scan line
  int64_t left_ticks = 0;
  int64_t right_ticks = 0;
};

// Parses one line. True with the record (kIgnored for line types the format
// does not read); false for a malformed line of a type it reads, with a short
// reason in *error (e.g. "FLASER: range 17 is not a number >= 0").
bool parse_dataset_record(DatasetFormat format, std::string_view line, DatasetRecord* record, std::string* error);

// Seconds since the epoch to microseconds; false for times no log can have
// (NaN, negative, or past the year 5000).
bool dataset_time_to_utime(double seconds, int64_t* utime);

}  // namespace slamer

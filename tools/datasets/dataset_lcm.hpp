// Writes an imported dataset (dataset_import.hpp) as an LCM log: LIDAR
// (laser_scan_t), ODOMETRY (odometry_t), WHEEL_ENCODERS (wheel_encoders_t)
// and GROUND_TRUTH (pose_estimate_t, covariance zero), each event stamped
// with its message's utime so offline replays see the recorded timing.
#pragma once

#include <string>

#include "tools/datasets/dataset_import.hpp"

namespace slamer {

struct DatasetChannels {
  std::string lidar = "LIDAR";
  std::string odometry = "ODOMETRY";
  std::string wheel_encoders = "WHEEL_ENCODERS";
  std::string ground_truth = "GROUND_TRUTH";
};

// Throws std::runtime_error if the log cannot be written.
void write_dataset_lcm(const ImportedLog& log, const std::string& path, const DatasetChannels& channels = {});

// One line: what was imported (scans, odometry, reference, retimed, malformed, laser mount).
std::string describe_import(const ImportedLog& log);

}  // namespace slamer

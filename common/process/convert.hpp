// Conversions between library types and LCM messages, for the thin mains.
#pragma once

#include "common/geometry/se2.hpp"
#include "common/semantic/objects.hpp"
#include "common/sensors/laser_scan.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/semantic_objects_t.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace slamer {

laser_scan_t to_message(const LaserScan& scan);
LaserScan from_message(const laser_scan_t& message);

odometry_t make_odometry(int64_t utime, int64_t seq, const Pose2& pose, double v, double omega);
wheel_encoders_t make_wheel_encoders(int64_t utime, int64_t seq, const std::string& source, int64_t left,
                                     int64_t right);
// A pose with zero covariance (ground truth), status OK.
pose_estimate_t make_exact_pose(int64_t utime, const Pose2& pose);

// Recognized objects (sensor frame) and semantic objects (map frame).
LineObjectSet from_message(const line_objects_t& message);
LineObjectSet from_message(const semantic_objects_t& message);
line_objects_t to_line_objects_message(const LineObjectSet& set, const std::string& frame);
semantic_objects_t to_semantic_objects_message(const LineObjectSet& set);

}  // namespace slamer

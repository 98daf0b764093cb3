#include "common/process/convert.hpp"

#include <algorithm>

namespace slamer {

laser_scan_t to_message(const LaserScan& scan) {
  laser_scan_t message;
  message.utime = scan.utime;
  message.sensor_utime = scan.sensor_utime;
  message.seq = scan.seq;
  message.frame = scan.frame;
  message.angle_min = scan.angle_min;
  message.angle_increment = scan.angle_increment;
  message.range_min = scan.range_min;
  message.range_max = scan.range_max;
  message.time_increment = scan.time_increment;
  message.scan_period = scan.scan_period;
  message.ranges = scan.ranges;
  message.nranges = static_cast<int32_t>(scan.ranges.size());
  message.intensities = scan.intensities;
  message.nintensities = static_cast<int32_t>(scan.intensities.size());
  return message;
}

LaserScan from_message(const laser_scan_t& message) {
  LaserScan scan;
  scan.utime = message.utime;
  scan.sensor_utime = message.sensor_utime;
  scan.seq = message.seq;
  scan.frame = message.frame;
  scan.angle_min = message.angle_min;
  scan.angle_increment = message.angle_increment;
  scan.range_min = message.range_min;
  scan.range_max = message.range_max;
  scan.time_increment = message.time_increment;
  scan.scan_period = message.scan_period;
  scan.ranges = message.ranges;
  scan.intensities = message.intensities;
  return scan;
}

odometry_t make_odometry(int64_t utime, int64_t seq, const Pose2& pose, double v, double omega) {
  odometry_t message;
  message.utime = utime;
  message.seq = seq;
  message.x = pose.x;
  message.y = pose.y;
  message.theta = pose.theta;
  message.v = v;
  message.omega = omega;
  return message;
}

wheel_encoders_t make_wheel_encoders(int64_t utime, int64_t seq, const std::string& source, int64_t left,
                                     int64_t right) {
  wheel_encoders_t message;
  message.utime = utime;
  message.seq = seq;
  message.source = source;
  message.ticks = {left, right};
  message.nwheels = 2;
  return message;
}

pose_estimate_t make_exact_pose(int64_t utime, const Pose2& pose) {
  pose_estimate_t message;
  message.utime = utime;
  message.x = pose.x;
  message.y = pose.y;
  message.theta = pose.theta;
  std::fill(std::begin(message.cov), std::end(message.cov), 0.0);
  message.nparticles = 0;
  message.ess = 0.0;
  message.status = pose_estimate_t::OK;
  return message;
}

LineObjectSet from_message(const line_objects_t& message) {
  LineObjectSet set{message.utime, message.seq, message.class_names, {}};
  for (const line_object_t& o : message.objects) {
    set.objects.push_back({static_cast<LineKind>(o.kind), {o.x1, o.y1}, {o.x2, o.y2}, o.npoints, o.probs, -1});
  }
  return set;
}

LineObjectSet from_message(const semantic_objects_t& message) {
  LineObjectSet set{message.utime, 0, message.class_names, {}};
  for (const semantic_object_t& o : message.objects) {
    set.objects.push_back({static_cast<LineKind>(o.kind), {o.x1, o.y1}, {o.x2, o.y2}, 0, o.probs, o.label});
  }
  return set;
}

namespace {

// The fields line_object_t and semantic_object_t share: kind, ends, probabilities.
template <class ObjectMsg>
ObjectMsg object_fields(const LineObject& o) {
  ObjectMsg object;
  object.kind = static_cast<int8_t>(o.kind);
  object.x1 = o.start.x();
  object.y1 = o.start.y();
  object.x2 = o.end.x();
  object.y2 = o.end.y();
  object.probs = o.probs;
  object.nclasses = static_cast<int32_t>(o.probs.size());
  return object;
}

}  // namespace

line_objects_t to_line_objects_message(const LineObjectSet& set, const std::string& frame) {
  line_objects_t message;
  message.utime = set.utime;
  message.seq = set.seq;
  message.frame = frame;
  message.class_names = set.class_names;
  message.nclasses = static_cast<int32_t>(set.class_names.size());
  for (const LineObject& o : set.objects) {
    line_object_t object = object_fields<line_object_t>(o);
    object.npoints = o.npoints;
    message.objects.push_back(object);
  }
  message.nobjects = static_cast<int32_t>(message.objects.size());
  return message;
}

semantic_objects_t to_semantic_objects_message(const LineObjectSet& set) {
  semantic_objects_t message;
  message.utime = set.utime;
  message.class_names = set.class_names;
  message.nclasses = static_cast<int32_t>(set.class_names.size());
  for (const LineObject& o : set.objects) {
    semantic_object_t object = object_fields<semantic_object_t>(o);
    object.label = o.label;
    message.objects.push_back(object);
  }
  message.nobjects = static_cast<int32_t>(message.objects.size());
  return message;
}

}  // namespace slamer

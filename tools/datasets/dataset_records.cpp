#include "tools/datasets/dataset_records.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "tools/datasets/tokens.hpp"

namespace slamer {
namespace {

using dataset_detail::Tokens;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kPi = std::numbers::pi;

bool fail(std::string* error, std::string text) {
  *error = std::move(text);
  return false;
}

void set_geometry(LaserScan* scan, double angle_min, double angle_increment, float range_max) {
  scan->angle_min = angle_min;
  scan->angle_increment = angle_increment;
  scan->range_min = 0.02f;
  scan->range_max = range_max;
  scan->frame = "laser";
}

// Reads `count` finite doubles into `values`.
bool finite_numbers(Tokens& tokens, double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!tokens.number(&values[i]) || !std::isfinite(values[i])) {
      return false;
    }
  }
  return true;
}

bool set_time(double seconds, DatasetRecord* record) {
  int64_t utime = 0;
  if (!dataset_time_to_utime(seconds, &utime)) {
    return false;
  }
  record->time = seconds;
  record->scan.utime = utime;
  record->scan.sensor_utime = utime;
  return true;
}

// Ranges in metres; values at or beyond `no_return` become +inf.
bool read_ranges(Tokens& tokens, int n, double no_return, LaserScan* scan) {
  scan->ranges.resize(static_cast<std::size_t>(n));
  for (float& r : scan->ranges) {
    double value = 0.0;
    if (!tokens.number(&value) || !std::isfinite(value) || value < 0.0) {
      return false;
    }
    r = value >= no_return ? kInf : static_cast<float>(value);
  }
  return true;
}

bool parse_flaser(Tokens& tokens, DatasetRecord* record, std::string* error) {
  int n = 0;
  if (!tokens.number(&n) || n <= 0 || n > 10000) {
    return fail(error, "FLASER: bad beam count");
  }
  // GMapping's CARMEN reader: 180/181 beams 1 deg apart, 360/361 0.5 deg, else 180 deg / n.
  double step = kPi / n;
  if (n == 181 || n == 361 || n == 541) {
    step = kPi / (n - 1);
  }
  set_geometry(&record->scan, -kPi / 2, step, 80.0f);
  // aces saturates at 50 m and fr079 writes 81.91 m: both mean no return.
  if (!read_ranges(tokens, n, 49.99, &record->scan)) {
    return fail(error, "FLASER: fewer than " + std::to_string(n) + " ranges >= 0");
  }
  double poses[6];
  double timestamp = 0.0;
  if (!finite_numbers(tokens, poses, 6) || !tokens.number(&timestamp)) {
    return fail(error, "FLASER: bad or missing pose or timestamp after the ranges");
  }
  if (!set_time(timestamp, record)) {
    return fail(error, "FLASER: timestamp out of range");
  }
  record->pose = {poses[0], poses[1], wrap_angle(poses[2])};
  record->base_pose = {poses[3], poses[4], wrap_angle(poses[5])};
  record->has_poses = true;
  return true;
}

bool parse_robotlaser(Tokens& tokens, DatasetRecord* record, std::string* error) {
  double config[6];  // type, start angle, fov, resolution, max range, accuracy
  int remission_mode = 0;
  int n = 0;
  if (!finite_numbers(tokens, config, 6) || !tokens.number(&remission_mode) || !tokens.number(&n) || n <= 0 ||
      n > 10000) {
    return fail(error, "ROBOTLASER1: bad laser configuration or beam count");
  }
  const double start = config[1];
  const double resolution = config[3];
  const double max_range = config[4];
  if (std::abs(start) > 2 * kPi || !(resolution > 0.0) || resolution * n > 2 * kPi + 1e-6 || !(max_range > 0.0) ||
      max_range > 1000.0) {
    return fail(error, "ROBOTLASER1: start angle, resolution or max range out of range");
  }
  set_geometry(&record->scan, start, resolution, static_cast<float>(max_range));
  if (!read_ranges(tokens, n, max_range - 1e-3, &record->scan)) {
    return fail(error, "ROBOTLASER1: fewer than " + std::to_string(n) + " ranges >= 0");
  }
  int m = 0;
  if (!tokens.number(&m) || m < 0 || m > 10000 || !tokens.skip(m)) {
    return fail(error, "ROBOTLASER1: bad remission count");
  }
  double poses[6];
  double rest[5];  // tv, rv, forward and side safety distances, turn axis
  double timestamp = 0.0;
  if (!finite_numbers(tokens, poses, 6) || !finite_numbers(tokens, rest, 5) || !tokens.number(&timestamp)) {
    return fail(error, "ROBOTLASER1: bad or missing poses or timestamp after the ranges");
  }
  if (!set_time(timestamp, record)) {
    return fail(error, "ROBOTLASER1: timestamp out of range");
  }
  record->pose = {poses[0], poses[1], wrap_angle(poses[2])};
  record->base_pose = {poses[3], poses[4], wrap_angle(poses[5])};
  record->has_poses = true;
  return true;
}

bool parse_odom(Tokens& tokens, DatasetRecord* record, std::string* error) {
  double values[6];  // x y th tv rv accel
  double timestamp = 0.0;
  if (!finite_numbers(tokens, values, 6) || !tokens.number(&timestamp) || std::isnan(timestamp)) {
    return fail(error, "ODOM: expected x y theta tv rv accel timestamp");
  }
  if (!set_time(timestamp, record)) {
    // Corrected logs stamp some re-anchoring lines with junk (fr079: -0.96, 9e-67): the
    // pose still counts; the time is marked unusable (-1) and the importer retimes it.
    record->time = timestamp;
    record->scan.utime = -1;
    record->scan.sensor_utime = -1;
  }
  record->pose = {values[0], values[1], wrap_angle(values[2])};
  record->v = values[3];
  record->omega = values[4];
  return true;
}

bool parse_carmen(Tokens& tokens, std::string_view tag, DatasetRecord* record, std::string* error) {
  if (tag == "FLASER") {
    record->kind = RecordKind::kScan;
    return parse_flaser(tokens, record, error);
  }
  if (tag == "ROBOTLASER1") {
    record->kind = RecordKind::kScan;
    return parse_robotlaser(tokens, record, error);
  }
  if (tag == "ODOM") {
    record->kind = RecordKind::kOdometry;
    return parse_odom(tokens, record, error);
  }
  return true;  // PARAM, NEFF, comments, other sensors
}

bool parse_cmu(Tokens& tokens, std::string_view tag, DatasetRecord* record, std::string* error) {
  if (tag == "O") {
    record->kind = RecordKind::kOdometry;
    double values[3];
    double timestamp = 0.0;
    if (!finite_numbers(tokens, values, 3) || !tokens.number(&timestamp) || !set_time(timestamp, record)) {
      return fail(error, "O: expected x y theta timestamp (cm, rad, s)");
    }
    record->pose = {values[0] * 0.01, values[1] * 0.01, wrap_angle(values[2])};
    return true;
  }
  if (tag != "L") {
    return true;
  }
  record->kind = RecordKind::kScan;
  double pose[6];
  if (!finite_numbers(tokens, pose, 6)) {
    return fail(error, "L: expected robot and laser poses (cm, rad)");
  }
  set_geometry(&record->scan, -kPi / 2, kPi / 180.0, 81.8f);
  record->scan.ranges.resize(180);
  for (float& r : record->scan.ranges) {
    int centimetres = 0;
    if (!tokens.number(&centimetres) || centimetres < 0) {
      return fail(error, "L: fewer than 180 ranges (integer cm >= 0)");
    }
    r = centimetres >= 8183 ? kInf : static_cast<float>(centimetres) * 0.01f;
  }
  double timestamp = 0.0;
  if (!tokens.number(&timestamp) || !set_time(timestamp, record)) {
    return fail(error, "L: bad or missing timestamp");
  }
  record->base_pose = {pose[0] * 0.01, pose[1] * 0.01, wrap_angle(pose[2])};
  record->pose = {pose[3] * 0.01, pose[4] * 0.01, wrap_angle(pose[5])};
  record->has_poses = true;
  return true;
}

bool parse_mines(Tokens& tokens, DatasetRecord* record, std::string* error) {
  record->kind = RecordKind::kScan;
  int64_t micros = 0;
  std::string_view unused;
  if (!tokens.number(&micros) || micros < 0 || micros > int64_t{100'000'000'000'000'000} || !tokens.next(&unused) ||
      !tokens.number(&record->left_ticks) || !tokens.number(&record->right_ticks) || !tokens.skip(20)) {
    return fail(error, "Mines: expected time [us], a field, left and right ticks and 20 more fields");
  }
  constexpr int kBeams = 682;
  const double fov = 240.0 * kPi / 180.0;
  set_geometry(&record->scan, -fov / 2, fov / (kBeams - 1), 5.6f);  // URG-04LX reads a little beyond 4 m
  record->scan.ranges.resize(kBeams);
  for (float& r : record->scan.ranges) {
    int millimetres = 0;
    if (!tokens.number(&millimetres) || millimetres < 0) {
      return fail(error, "Mines: fewer than 682 ranges (integer mm >= 0)");
    }
    r = millimetres == 0 ? kInf : static_cast<float>(millimetres) * 0.001f;
  }
  record->has_ticks = true;
  record->time = static_cast<double>(micros) * 1e-6;
  record->scan.utime = micros;
  record->scan.sensor_utime = micros;
  return true;
}

}  // namespace

bool dataset_time_to_utime(double seconds, int64_t* utime) {
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > 1e11) {
    return false;
  }
  *utime = static_cast<int64_t>(std::llround(seconds * 1e6));
  return true;
}

bool parse_dataset_record(DatasetFormat format, std::string_view line, DatasetRecord* record, std::string* error) {
  *record = DatasetRecord{};
  Tokens tokens(line);
  if (format == DatasetFormat::kMines) {
    Tokens probe(line);
    std::string_view first;
    if (!probe.next(&first)) {
      return true;  // a blank line
    }
    return parse_mines(tokens, record, error);
  }
  std::string_view tag;
  if (!tokens.next(&tag)) {
    return true;
  }
  record->tag = std::string(tag);
  return format == DatasetFormat::kCarmen ? parse_carmen(tokens, tag, record, error)
                                          : parse_cmu(tokens, tag, record, error);
}

}  // namespace slamer

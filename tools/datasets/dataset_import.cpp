#include "tools/datasets/dataset_import.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tools/datasets/dataset_lines.hpp"

namespace slamer {
namespace {

constexpr int64_t kMinScanStep = 1'000;        // [us]
constexpr int64_t kNominalScanStep = 100'000;  // [us]
constexpr int64_t kRetimeStep = 1'000;         // [us]

bool same_pose(const Pose2& a, const Pose2& b) {
  return std::abs(a.x - b.x) < 1e-3 && std::abs(a.y - b.y) < 1e-3 && std::abs(angle_diff(a.theta, b.theta)) < 1e-3;
}

// The robot pose a scan line states as its reference.
Pose2 reference_of(const DatasetRecord& r) {
  return r.tag == "ROBOTLASER1" ? r.base_pose : r.pose;
}

std::vector<DatasetRecord> read_records(const std::string& path, const ImportOptions& options, ImportedLog* log) {
  DatasetLineReader reader(path);
  std::vector<DatasetRecord> records;
  std::string line;
  while (reader.next(&line)) {
    DatasetRecord record;
    std::string error;
    if (!parse_dataset_record(options.format, line, &record, &error)) {
      ++log->malformed;
      if (log->errors.size() < options.max_errors_kept) {
        log->errors.push_back(path + ":" + std::to_string(reader.line_number()) + ": " + error);
      }
    } else if (record.kind != RecordKind::kIgnored) {
      records.push_back(std::move(record));
    }
  }
  log->lines = reader.line_number();
  return records;
}

bool looks_corrected(const std::vector<DatasetRecord>& records) {
  int checked = 0;
  int matching = 0;
  for (std::size_t i = 0; i + 1 < records.size(); ++i) {
    if (records[i].kind == RecordKind::kScan && records[i + 1].kind == RecordKind::kOdometry) {
      // Re-anchoring: the scan's own pose, stamped 0 or junk (a raw log's next ODOM is later).
      ++checked;
      matching += same_pose(records[i + 1].pose, reference_of(records[i])) &&
                          records[i + 1].scan.sensor_utime < records[i].scan.sensor_utime
                      ? 1
                      : 0;
    }
  }
  return checked > 0 && matching * 10 >= checked * 9;
}

void add_scan(DatasetRecord& record, int64_t utime, ImportedLog* log) {
  record.scan.utime = utime;
  record.scan.seq = static_cast<int64_t>(log->scans.size());
  if (!log->laser_mount && record.has_poses && record.tag != "FLASER") {
    log->laser_mount = between(record.base_pose, record.pose);  // ROBOTLASER1 and CMU state both poses
  }
  log->scans.push_back(std::move(record.scan));
}

void import_corrected(std::vector<DatasetRecord>& records, ImportedLog* log) {
  log->corrected = true;
  std::vector<std::size_t> scan_at;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].kind == RecordKind::kScan) {
      scan_at.push_back(i);
    }
  }
  if (scan_at.empty()) {
    return;
  }
  Pose2 raw = scan_at[0] > 0 ? records[scan_at[0] - 1].pose : reference_of(records[scan_at[0]]);
  // A log whose times mostly do not advance from scan to scan (csail prints
  // 6 significant digits: one value for 365 scans, then a step of 10^4 s)
  // has no time base at all: every scan then goes at the nominal period, or
  // the rare steps of the printed time would become gaps of hours.
  std::size_t stuck = 0;
  for (std::size_t k = 1; k < scan_at.size(); ++k) {
    stuck += records[scan_at[k]].scan.sensor_utime < records[scan_at[k - 1]].scan.sensor_utime + kMinScanStep;
  }
  const bool no_time_base = 2 * stuck > scan_at.size();
  int64_t previous = 0;
  std::vector<int64_t> utimes;
  for (std::size_t k = 0; k < scan_at.size(); ++k) {
    const DatasetRecord& r = records[scan_at[k]];
    int64_t utime = r.scan.sensor_utime;
    if (k > 0 && (no_time_base || utime < previous + kMinScanStep)) {
      utime = previous + kNominalScanStep;
      ++log->retimed;
    }
    utimes.push_back(utime);
    previous = utime;
  }
  for (std::size_t k = 0; k < scan_at.size(); ++k) {
    DatasetRecord& scan = records[scan_at[k]];
    const Pose2 reference = reference_of(scan);
    log->reference.push_back(reference);
    log->scan_odometry.push_back(raw);
    log->odometry.push_back({utimes[k], raw});
    add_scan(scan, utimes[k], log);
    if (k + 1 == scan_at.size()) {
      break;
    }
    const std::size_t first = scan_at[k] + 1;
    const std::size_t end = scan_at[k + 1];
    if (first == end) {
      ++log->empty_intervals;
      continue;
    }
    const Pose2 anchor = records[first].pose;
    log->reanchor_mismatches += same_pose(anchor, reference) ? 0 : 1;
    const Pose2 start = raw;
    const int64_t span = utimes[k + 1] - utimes[k];
    const auto count = static_cast<int64_t>(end - first);
    for (std::size_t j = first; j < end; ++j) {
      raw = compose(start, between(anchor, records[j].pose));
      const auto step = static_cast<int64_t>(j - first);
      if (step > 0 && j + 1 < end && span / count > 0) {
        log->odometry.push_back({utimes[k] + step * span / count, raw});
      }
    }
  }
}

// Raw streams in file order on one clock.
void import_in_order(std::vector<DatasetRecord>& records, const ImportOptions& options, ImportedLog* log) {
  int64_t previous = -1;
  const double metres_per_tick = 2.0 * std::numbers::pi * options.mines_wheel_radius / options.mines_ticks_per_rev;
  std::optional<TickSample> last_ticks;
  Pose2 mines_pose;
  for (DatasetRecord& r : records) {
    int64_t utime = r.scan.sensor_utime;
    if (utime <= previous) {
      utime = previous + kRetimeStep;
      ++log->retimed;
    }
    previous = utime;
    if (r.kind == RecordKind::kOdometry) {
      log->odometry.push_back({utime, r.pose});
      continue;
    }
    if (r.has_ticks) {
      if (last_ticks) {
        const double left = static_cast<double>(r.left_ticks - last_ticks->left) * metres_per_tick;
        const double right = static_cast<double>(r.right_ticks - last_ticks->right) * metres_per_tick;
        const Twist2 twist{(left + right) / 2.0, 0.0, (right - left) / (2.0 * options.mines_half_axle)};
        mines_pose = compose(mines_pose, exp_se2(twist));
      }
      last_ticks = TickSample{utime, r.left_ticks, r.right_ticks};
      log->ticks.push_back(*last_ticks);
      log->odometry.push_back({utime, mines_pose});
      log->laser_mount = options.mines_laser_mount;
    } else if (r.has_poses && options.format == DatasetFormat::kCmu) {
      log->odometry.push_back({utime, r.base_pose});  // the L line's own odometry pose
    }
    log->scan_odometry.push_back(r.has_ticks ? mines_pose : r.base_pose);
    add_scan(r, utime, log);
  }
}

void fill_velocities(std::vector<TimedPose>* odometry) {
  for (std::size_t i = 1; i < odometry->size(); ++i) {
    TimedPose& p = (*odometry)[i];
    const TimedPose& q = (*odometry)[i - 1];
    const double dt = static_cast<double>(p.utime - q.utime) * 1e-6;
    const Twist2 twist = log_se2(between(q.pose, p.pose));
    p.v = dt > 0.0 ? twist.vx / dt : 0.0;
    p.omega = dt > 0.0 ? twist.omega / dt : 0.0;
  }
}

}  // namespace

ImportedLog import_dataset(const std::string& path, const ImportOptions& options) {
  ImportedLog log;
  std::vector<DatasetRecord> records = read_records(path, options, &log);
  const bool corrected = options.format == DatasetFormat::kCarmen &&
                         (options.corrected == ImportOptions::Corrected::kYes ||
                          (options.corrected == ImportOptions::Corrected::kAuto && looks_corrected(records)));
  if (corrected) {
    import_corrected(records, &log);
  } else {
    import_in_order(records, options, &log);
  }
  fill_velocities(&log.odometry);
  return log;
}

std::vector<StreamEntry> merge_streams(const ImportedLog& log) {
  std::vector<StreamEntry> entries;
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    entries.push_back({StreamKind::kOdometry, i, log.odometry[i].utime});
  }
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    entries.push_back({StreamKind::kTicks, i, log.ticks[i].utime});
  }
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    entries.push_back({StreamKind::kScan, i, log.scans[i].utime});
    if (i < log.reference.size()) {
      entries.push_back({StreamKind::kGroundTruth, i, log.scans[i].utime});
    }
  }
  std::stable_sort(entries.begin(), entries.end(), [](const StreamEntry& a, const StreamEntry& b) {
    return a.utime != b.utime ? a.utime < b.utime : static_cast<int>(a.kind) < static_cast<int>(b.kind);
  });
  return entries;
}

OdometryDrift odometry_drift(const ImportedLog& log) {
  OdometryDrift drift;
  const std::size_t n = std::min(log.reference.size(), log.scan_odometry.size());
  if (n < 2) {
    return drift;
  }
  std::vector<double> path(n, 0.0);  // reference path length up to each scan
  Pose2 dead = log.reference[0];
  double step_position = 0.0;
  double step_heading = 0.0;
  for (std::size_t k = 1; k < n; ++k) {
    const Pose2 odom_step = between(log.scan_odometry[k - 1], log.scan_odometry[k]);
    const Pose2 ref_step = between(log.reference[k - 1], log.reference[k]);
    path[k] = path[k - 1] + std::hypot(ref_step.x, ref_step.y);
    step_position += std::hypot(odom_step.x - ref_step.x, odom_step.y - ref_step.y);
    step_heading += std::abs(angle_diff(odom_step.theta, ref_step.theta));
    dead = compose(dead, odom_step);
    const double error = std::hypot(dead.x - log.reference[k].x, dead.y - log.reference[k].y);
    drift.max_position_error = std::max(drift.max_position_error, error);
    drift.final_position_error = error;
  }
  drift.path_length = path[n - 1];
  drift.step_position_error = step_position / static_cast<double>(n - 1);
  drift.step_heading_error_deg = step_heading / static_cast<double>(n - 1) * 180.0 / std::numbers::pi;
  // Heading error gathered over each 1 m stretch of the reference path.
  double sum = 0.0;
  int windows = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    j = std::max(j, i);
    while (j < n && path[j] - path[i] < 1.0) {
      ++j;
    }
    if (j >= n) {
      break;
    }
    const double odom_turn = angle_diff(log.scan_odometry[j].theta, log.scan_odometry[i].theta);
    const double ref_turn = angle_diff(log.reference[j].theta, log.reference[i].theta);
    sum += std::abs(angle_diff(odom_turn, ref_turn)) / (path[j] - path[i]);
    ++windows;
  }
  drift.heading_deg_per_m = windows > 0 ? sum / windows * 180.0 / std::numbers::pi : 0.0;
  return drift;
}

}  // namespace slamer

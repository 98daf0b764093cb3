// slamer-bench's scoring: one localizer pose per scan of a log, its error
// against the log's reference (a corrected CARMEN log's GMapping estimate,
// not ground truth), and the outputs: poses.txt (`t x y theta status`, one
// line per scan, t the log's own time), summary.json (position / heading
// error mean, std, max; fraction lost = error > 0.5 m; time per scan; the
// status-versus-error confusion table) and errors.png (error and status over
// time). Started by global localization (`--global`), the scoring also says
// from which scan the estimate is right to the end and from which it says OK.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/stats/status_honesty.hpp"

namespace slamer {

using BenchStatus = ReportedStatus;  // pose_estimate_t status values
const char* status_name(BenchStatus status);

struct PoseReport {
  int64_t utime = 0;  // the scan's utime (POSE.utime)
  Pose2 pose;
  BenchStatus status = BenchStatus::kInitializing;
};

struct BenchPose {
  double t = 0.0;  // the log's own time of the scan [s]
  Pose2 pose;
  BenchStatus status = BenchStatus::kInitializing;
  bool has_report = true;  // false: no POSE for this scan, the previous pose repeated
  int64_t utime = 0;       // the scan's utime as sent (strictly increasing; the log's time where it has one)
};

// One pose per scan (scan_utimes strictly increasing): the POSE with the
// scan's utime, else the previous one (the initial pose, INITIALIZING, before
// the first). *missing counts the scans without a POSE.
std::vector<BenchPose> poses_per_scan(const std::vector<int64_t>& scan_utimes, const std::vector<int64_t>& log_utimes,
                                      const std::vector<PoseReport>& reports, const Pose2& initial_pose,
                                      int64_t* missing);

struct ErrorStats {
  double mean = 0.0;
  double std = 0.0;
  double max = 0.0;
};

struct BenchScore {
  int64_t scans = 0;
  int64_t scans_without_pose = 0;
  ErrorStats position;  // [m]
  ErrorStats heading;   // [rad]
  double fraction_lost = 0.0;
  // rows: status (INITIALIZING, OK, UNCERTAIN, LOST); columns: error < 0.2 m, 0.2-0.5 m, > 0.5 m.
  std::array<std::array<int64_t, 3>, 4> confusion{};
  StatusHonesty honesty;  // issue 9's honest-status bars
  // The first scan from which the position error stays <= 0.5 m to the end but for blips, and the
  // first scan from there that says OK; none: the last scan is off. A blip is off by at most 1 m for
  // under 2 s (the honesty count's grace): a reference or scan-match blip, not a wrong place
  // (far_after_right counts their scans); a stretch off from the first scan is a global
  // localization's search, however short. Seconds from the first scan by utime (csail's log has no
  // time base: its scans go at a nominal 10 Hz, dataset_import.hpp).
  std::optional<int64_t> right_from;
  double right_from_seconds = 0.0;
  int64_t far_after_right = 0;
  std::optional<int64_t> ok_from;
  double ok_from_seconds = 0.0;
  std::vector<double> position_errors;  // per scan [m]
};

// Throws std::invalid_argument if the sizes differ.
BenchScore score_poses(const std::vector<BenchPose>& poses, const std::vector<Pose2>& reference);

std::string format_poses(const std::vector<BenchPose>& poses);

// "within 0.5 m to the end from scan N (T s) (then B scans in blips ...), OK from scan M (T s);
// OK while > 0.5 m off in K scans" ("never" where there is no such scan).
std::string describe_right_from(const BenchScore& score);

struct BenchRunInfo {
  std::string log;
  std::string mode;
  int particles = 0;
  std::string beams;
  int64_t seed = 0;
  double wall_seconds = 0.0;         // the localizer's run
  double cpu_seconds = 0.0;          // its user + system time
  std::string command;               // the localizer command line
  double startup_cpu_seconds = 0.0;  // the same on the first scan alone (loading the map, building fields)
  bool global = false;               // started by global localization, not at the first reference pose
  std::optional<std::pair<std::size_t, std::size_t>> kidnap;  // scans [first, second) of the log left out (kidnapped())
};
std::string summary_json(const BenchScore& score, const BenchRunInfo& info);

// "N scans: position error mean ... cm (std, max), heading ... deg, lost ... %, status: ... % of K far
// flagged after 2 s, ... % of close LOST, ... ms per scan (CPU, start-up excluded)".
std::string describe_score(const BenchScore& score, const BenchRunInfo& info);

// Position error over time with each scan's status as a coloured strip;
// throws std::runtime_error if the PNG cannot be written.
void write_bench_plot(const std::vector<BenchPose>& poses, const BenchScore& score, const std::string& title,
                      const std::string& png_path);

}  // namespace slamer

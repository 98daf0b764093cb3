#include "tools/datasets/bench_files.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "common/config/config_reader.hpp"
#include "common/process/command_line.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "slamer/pose_estimate_t.hpp"

namespace slamer {

std::string dataset_robot_yaml(const std::string& name, const LaserScan& scan, const Pose2& mount) {
  const int beams = static_cast<int>(scan.ranges.size());
  const double angle_max = scan.angle(scan.ranges.empty() ? 0 : scan.ranges.size() - 1);
  char text[1200];
  std::snprintf(text, sizeof text,
                "# Written by slamer-bench for %s: the laser where the log puts it (at the robot origin\n"
                "# unless the log states an offset), its beam geometry from the first scan.\n"
                "name: dataset\n"
                "# Not an i-Cart, and a retimed log (csail) has no real time base between scans:\n"
                "# speed limits far above any robot's, so the localizer's odometry-jump check\n"
                "# (speed over the interval) only catches absurd steps here.\n"
                "base:\n"
                "  max_speed: 100.0\n"
                "  max_yaw_rate: 100.0\n"
                "lidar:\n"
                "  frame: laser\n"
                "  mount: [%.4f, %.4f, %.5f]\n"
                "  angle_min: %.8f\n"
                "  angle_max: %.8f\n"
                "  beams: %d\n"
                "  scan_period: %.3f\n"
                "  range_min: %.3f\n"
                "  range_max: %.3f\n",
                name.c_str(), mount.x, mount.y, mount.theta, scan.angle_min, angle_max, std::max(beams, 2),
                scan.scan_period > 0.0f ? scan.scan_period : 0.2, scan.range_min, scan.range_max);
  return text;
}

std::string bench_localizer_config(const std::string& base_config, const BenchConfigChanges& changes) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(base_config);
  } catch (const YAML::Exception& e) {
    throw ConfigError(base_config + ": " + e.msg);
  }
  if (!root.IsMap() || !root["localizer"].IsMap()) {
    throw ConfigError(base_config + ": expected a localizer config with a 'localizer' section");
  }
  root["map"] = changes.map;
  root["robot"] = changes.robot;
  root["localizer"]["particles"] = changes.particles;
  root["localizer"]["lfm"]["beam_step"] = changes.beam_step;
  std::ostringstream out;
  out << "# " << base_config << " with slamer-bench's particles, beam_step, map and robot.\n" << root << "\n";
  return out.str();
}

ImportedLog first_scan_only(const ImportedLog& log) {
  ImportedLog first;
  if (log.scans.empty()) {
    return first;
  }
  first.scans.push_back(log.scans.front());
  first.reference.assign(log.reference.begin(), log.reference.begin() + (log.reference.empty() ? 0 : 1));
  for (const TimedPose& p : log.odometry) {
    if (p.utime <= log.scans.front().utime) {
      first.odometry.push_back(p);
    }
  }
  first.corrected = log.corrected;
  return first;
}

ImportedLog kidnapped(const ImportedLog& log, std::size_t from, std::size_t to) {
  const std::size_t n = log.scans.size();
  if (!(0 < from && from < to && to < n) || log.scan_odometry.size() != n || log.reference.size() != n) {
    throw std::invalid_argument("a kidnap needs 0 < FROM < TO < " + std::to_string(n) +
                                " (the scans) and a corrected log");
  }
  const int64_t gap_start = log.scans[from].utime;
  const int64_t gap_end = log.scans[to].utime;
  const int64_t shift = gap_end - gap_start;
  // Odometry after the carry continues from where it stood at scan `from`.
  const Pose2 reanchor = compose(log.scan_odometry[from], inverse(log.scan_odometry[to]));
  ImportedLog out = log;
  out.scans.clear();
  out.reference.clear();
  out.scan_odometry.clear();
  out.odometry.clear();
  out.ticks.clear();
  for (std::size_t k = 0; k < n; ++k) {
    if (k >= from && k < to) {
      continue;
    }
    LaserScan scan = log.scans[k];
    if (k >= to) {
      scan.utime -= shift;
      scan.seq -= static_cast<int64_t>(to - from);
    }
    out.scans.push_back(std::move(scan));
    out.reference.push_back(log.reference[k]);
    out.scan_odometry.push_back(k >= to ? compose(reanchor, log.scan_odometry[k]) : log.scan_odometry[k]);
  }
  for (const TimedPose& p : log.odometry) {
    if (p.utime < gap_start) {
      out.odometry.push_back(p);
    } else if (p.utime >= gap_end) {
      out.odometry.push_back({p.utime - shift, compose(reanchor, p.pose), p.v, p.omega});
    }
  }
  return out;
}

std::vector<std::string> bench_localizer_args(const BenchLocalizerRun& run, const std::string& in,
                                              const std::string& out) {
  std::vector<std::string> args{"--config", run.config, "--map", run.map, "--robot", run.robot};
  if (run.start) {
    args.push_back("--initial-pose");
    for (const double v : {run.start->x, run.start->y, run.start->theta}) {
      args.push_back(std::to_string(v));
    }
  } else {
    args.push_back("--global");
  }
  args.insert(args.end(), {"--mode", run.mode, "--seed", run.seed, "--replay", in, "--out", out});
  return args;
}

std::pair<std::size_t, std::size_t> kidnap_scans(const std::vector<double>& values, std::size_t scans) {
  if (values.size() != 2 || values[0] < 1 || values[1] <= values[0] || values[1] >= static_cast<double>(scans) ||
      values[0] != std::floor(values[0]) || values[1] != std::floor(values[1])) {
    throw CommandLineError("--kidnap FROM TO needs scan numbers 0 < FROM < TO < " + std::to_string(scans));
  }
  return {static_cast<std::size_t>(values[0]), static_cast<std::size_t>(values[1])};
}

std::vector<BenchPose> poses_per_scan(const ImportedLog& log, const std::vector<PoseReport>& reports,
                                      const Pose2& initial_pose, int64_t* missing) {
  std::vector<int64_t> utimes;
  std::vector<int64_t> log_utimes;
  for (const LaserScan& scan : log.scans) {
    utimes.push_back(scan.utime);
    log_utimes.push_back(scan.sensor_utime);
  }
  return poses_per_scan(utimes, log_utimes, reports, initial_pose, missing);
}

std::vector<BenchPose> with_carried_scans(const std::vector<BenchPose>& kept, const ImportedLog& whole,
                                          std::size_t from, std::size_t to) {
  if (from == 0 || to <= from || to >= whole.scans.size() || kept.size() != whole.scans.size() - (to - from)) {
    throw std::invalid_argument("with_carried_scans: " + std::to_string(kept.size()) + " poses for a log of " +
                                std::to_string(whole.scans.size()) + " scans carried from " + std::to_string(from) +
                                " to " + std::to_string(to));
  }
  std::vector<BenchPose> poses(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(from));
  for (std::size_t k = from; k < to; ++k) {
    BenchPose unseen = kept[from - 1];
    unseen.t = static_cast<double>(whole.scans[k].sensor_utime) * 1e-6;
    unseen.has_report = false;
    poses.push_back(unseen);
  }
  poses.insert(poses.end(), kept.begin() + static_cast<std::ptrdiff_t>(from), kept.end());
  return poses;
}

std::string describe_kidnap(const ImportedLog& whole, const ImportedLog& kidnapped_log, std::size_t from) {
  const std::size_t to = from + whole.scans.size() - kidnapped_log.scans.size();
  const Pose2 moved = between(whole.reference.at(from), whole.reference.at(to));
  char text[200];
  std::snprintf(text, sizeof text,
                "kidnap: scans %zu-%zu left out; at scan %zu (%.1f s into the run) the robot was carried %.1f m and "
                "%.0f deg unseen",
                from, to - 1, from,
                static_cast<double>(kidnapped_log.scans.at(from).utime - kidnapped_log.scans.front().utime) * 1e-6,
                std::hypot(moved.x, moved.y), std::abs(moved.theta) * 180.0 / std::numbers::pi);
  return text;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) {
    throw std::runtime_error("cannot write " + path);
  }
}

std::vector<PoseReport> read_pose_reports(const std::string& lcm_path, const std::string& channel) {
  EventLogReader reader(lcm_path);
  std::vector<PoseReport> reports;
  while (const std::optional<LogEvent> event = reader.next()) {
    pose_estimate_t m;
    if (event->channel != channel || decode_message(event->data.data(), event->data.size(), &m) != DecodeStatus::kOk) {
      continue;
    }
    if (const std::optional<BenchStatus> status = reported_status(m.status)) {
      reports.push_back({m.utime, {m.x, m.y, m.theta}, *status});
    }
  }
  return reports;
}

}  // namespace slamer

#include "tools/datasets/bench_files.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/config/config_reader.hpp"
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

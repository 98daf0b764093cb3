// localizer_status_report: how honest a localizer run's POSE.status is (issue 9).
// For each output log of slamer-localizer on a simulated run: pose error mean /
// max, the fraction of scans lost (error > 0.5 m), the fraction of OK /
// UNCERTAIN / LOST per error band, how many scans more than 0.5 m off still
// say OK 2 s or more after the error passed 0.5 m, and the scan fit (the
// fraction of beams ending within 0.1 m of an obstacle of the map) at the true
// pose and at the estimate. With --odometry it reports the dead reckoning's
// heading drift per metre of path instead. A measurement program, not a test.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"
#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/robot/robot_options.hpp"
#include "common/stats/status_honesty.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "tools/sim/world.hpp"

namespace slamer {
namespace {

struct Scan {
  Pose2 truth;
  std::optional<Pose2> estimate;
  int status = -1;
  std::optional<Pose2> odometry;
  double fit_truth = 0.0, fit_estimate = 0.0;
};

double fit(const DistanceField& field, const Pose2& base, const Pose2& mount, const LaserScan& scan) {
  const Pose2 sensor = compose(base, mount);
  int used = 0, near = 0;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!(r >= scan.range_min && r < scan.range_max))
      continue;
    ++used;
    const double a = sensor.theta + scan.angle(i);
    const auto d = field.at_world({sensor.x + r * std::cos(a), sensor.y + r * std::sin(a)});
    near += d && *d <= 0.1f ? 1 : 0;
  }
  return used > 0 ? static_cast<double>(near) / used : 0.0;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

int report(const std::string& path, const DistanceField& field, const Pose2& mount, bool odometry_only) {
  std::map<int64_t, Scan> scans;
  std::vector<std::pair<int64_t, Pose2>> odometry;
  std::map<int64_t, LaserScan> lidar;
  EventLogReader log(path);
  while (const auto event = log.next()) {
    if (event->channel == "GROUND_TRUTH" || event->channel == "POSE") {
      pose_estimate_t m{};
      if (decode_message(event->data.data(), event->data.size(), &m) != DecodeStatus::kOk)
        continue;
      if (event->channel == "GROUND_TRUTH") {
        scans[m.utime].truth = {m.x, m.y, m.theta};
      } else {
        scans[m.utime].estimate = Pose2{m.x, m.y, m.theta};
        scans[m.utime].status = m.status;
      }
    } else if (event->channel == "ODOMETRY") {
      odometry_t m{};
      if (decode_message(event->data.data(), event->data.size(), &m) == DecodeStatus::kOk) {
        odometry.emplace_back(m.utime, Pose2{m.x, m.y, m.theta});
      }
    } else if (event->channel == "LIDAR" && !odometry_only) {
      laser_scan_t m{};
      if (decode_message(event->data.data(), event->data.size(), &m) == DecodeStatus::kOk) {
        lidar[m.utime] = from_message(m);
      }
    }
  }
  if (odometry_only) {
    // Heading drift of dead reckoning against the truth, per metre of true path (1 m pieces).
    std::size_t k = 0;
    double path_length = 0.0, drift = 0.0, total_path = 0.0;
    std::optional<Pose2> prev_truth, start_truth, start_odom;
    std::vector<double> per_metre;
    for (auto& [utime, s] : scans) {
      while (k + 1 < odometry.size() && odometry[k + 1].first <= utime)
        ++k;
      if (odometry.empty())
        break;
      const Pose2 odom = odometry[k].second;
      if (prev_truth) {
        path_length += std::hypot(s.truth.x - prev_truth->x, s.truth.y - prev_truth->y);
      } else {
        start_truth = s.truth;
        start_odom = odom;
      }
      prev_truth = s.truth;
      if (path_length >= 1.0) {
        const double d =
            angle_diff(angle_diff(odom.theta, start_odom->theta), angle_diff(s.truth.theta, start_truth->theta));
        per_metre.push_back(std::abs(d) / path_length * 180.0 / M_PI);
        drift += std::abs(d);
        total_path += path_length;
        path_length = 0.0;
        start_truth = s.truth;
        start_odom = odom;
      }
    }
    std::printf("%s: odometry heading drift %.2f deg/m (mean of %zu 1 m pieces; median %.2f, p90 %.2f)\n", path.c_str(),
                drift / std::max(total_path, 1e-9) * 180.0 / M_PI, per_metre.size(), percentile(per_metre, 0.5),
                percentile(per_metre, 0.9));
    return 0;
  }
  const char* bands[3] = {"< 0.2 m", "0.2-0.5 m", "> 0.5 m"};
  double counts[3][3] = {};  // band x (OK, UNCERTAIN, LOST)
  double n_band[3] = {};
  double sum = 0.0, max = 0.0;
  int n = 0, far_ok = 0;
  StatusHonesty honesty;
  std::vector<double> fit_truth, fit_est[3];
  for (auto& [utime, s] : scans) {
    if (!s.estimate || s.status < pose_estimate_t::OK)
      continue;
    const double e = std::hypot(s.estimate->x - s.truth.x, s.estimate->y - s.truth.y);
    sum += e;
    max = std::max(max, e);
    ++n;
    const int band = e < 0.2 ? 0 : e <= 0.5 ? 1 : 2;
    const int st = s.status == pose_estimate_t::OK ? 0 : s.status == pose_estimate_t::UNCERTAIN ? 1 : 2;
    counts[band][st] += 1;
    n_band[band] += 1;
    far_ok += band == 2 && st == 0;
    honesty.add(static_cast<double>(utime) * 1e-6, e, static_cast<ReportedStatus>(s.status));
    const auto scan = lidar.find(utime);
    if (scan != lidar.end() && n % 4 == 0) {
      fit_truth.push_back(fit(field, s.truth, mount, scan->second));
      fit_est[band].push_back(fit(field, *s.estimate, mount, scan->second));
    }
  }
  std::printf("%s: %d scans, error mean %.2f cm max %.2f cm, lost %.2f %%\n", path.c_str(), n,
              100.0 * sum / std::max(n, 1), 100.0 * max, 100.0 * n_band[2] / std::max(n, 1));
  for (int b = 0; b < 3; ++b) {
    std::printf("  error %-9s %6.0f scans: OK %6.2f %%  UNCERTAIN %6.2f %%  LOST %6.2f %%\n", bands[b], n_band[b],
                100.0 * counts[b][0] / std::max(n_band[b], 1.0), 100.0 * counts[b][1] / std::max(n_band[b], 1.0),
                100.0 * counts[b][2] / std::max(n_band[b], 1.0));
  }
  std::printf(
      "  > 0.5 m and OK: %d scans; > 0.5 m for 2 s or more: %lld scans, of which OK %lld (%.2f %% "
      "UNCERTAIN/LOST)\n",
      far_ok, static_cast<long long>(honesty.far_after_grace()), static_cast<long long>(honesty.far_after_grace_ok()),
      100.0 * honesty.far_flagged_fraction());
  std::printf("  fit at truth p1 %.2f p5 %.2f p50 %.2f; at estimate p5/p50:", percentile(fit_truth, 0.01),
              percentile(fit_truth, 0.05), percentile(fit_truth, 0.5));
  for (int b = 0; b < 3; ++b) {
    std::printf(" [%s] %.2f/%.2f", bands[b], percentile(fit_est[b], 0.05), percentile(fit_est[b], 0.5));
  }
  std::printf("\n");
  return 0;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: localizer_status_report [--odometry] WORLD.yaml LOG...\n");
    return 2;
  }
  int first = 1;
  const bool odometry_only = std::string(argv[1]) == "--odometry";
  first += odometry_only ? 1 : 0;
  try {
    const auto world = slamer::load_options<slamer::WorldOptions>(argv[first]);
    const auto robot = slamer::load_options<slamer::RobotOptions>(world.robot_path);
    const slamer::SemanticMap map = slamer::load_semantic_map(world.map_path);
    const slamer::DistanceField field = slamer::obstacle_distance_field(map, 0.5);
    for (int i = first + 1; i < argc; ++i) {
      slamer::report(argv[i], field, robot.lidar.mount, odometry_only);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "localizer_status_report: %s\n", e.what());
    return 1;
  }
  return 0;
}

// End to end: the simulated robot through the real drivers. slamer-sim (live,
// --speed 1, config/sim_drivers.yaml) publishes SIM_LIDAR and
// SIM_WHEEL_ENCODERS; slamer-urg-sim and slamer-tfrog-sim turn them into SCIP
// over loopback TCP and the T-frog stream on a pty; the real slamer-urg and
// slamer-wheels (config/urg_sim.yaml, config/wheels_sim.yaml) publish LIDAR
// and ODOMETRY. Checked: every simulated scan after the driver's start-up is on
// LIDAR exactly once, with the same ranges (mm quantization, the same REP 117
// classes) and |utime - simulated utime| within the clock model's accuracy
// (p99 < 1 ms, every scan < 2 ms); every ODOMETRY pose is SIM_ODOMETRY's at
// the same wheel counts within 1 mm / 0.05 deg, and the track ends on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "common/geometry/se2.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/process_status_t.hpp"
#include "slamer/wheel_encoders_t.hpp"
#include "test/support/driver_processes.hpp"
#include "test/support/lcm_test_bus.hpp"

namespace slamer {
namespace {

// A file of the test's, removed at its end however it ends.
struct TempFile {
  std::string path;
  ~TempFile() { std::filesystem::remove(path); }
};

// small_room's first half: 3 m out, a half turn, 2 m back (about 13 s).
std::string write_world() {
  const std::string path = test::temp_path("sim_drivers_world") + ".yaml";
  const std::string root = SLAMER_SOURCE_DIR;
  std::ofstream(path) << "map: " << root << "/config/maps/small_room/map.yaml\n"
                      << "robot: " << root << "/config/robots/icart_mini.yaml\n"
                      << "start: [1.5, 3.0, 0.0]\n"
                      << "path:\n"
                      << "  - {go_to: [4.5, 3.0], speed: 0.5}\n"
                      << "  - {turn_to: 3.14159}\n"
                      << "  - {go_to: [2.5, 3.0], speed: 0.5}\n"
                      << "truth:\n"
                      << "  doors:\n"
                      << "    - {near: [6.0, 3.0], state: open}\n";
  return path;
}

// The REP 117 class of a range and, for finite ones, the value in whole mm.
bool same_range(float driver, float sim) {
  if (std::isnan(sim) || std::isnan(driver)) {
    return std::isnan(sim) && std::isnan(driver);
  }
  if (std::isinf(sim) || std::isinf(driver)) {
    return sim == driver;
  }
  return std::fabs(static_cast<double>(driver) - std::round(static_cast<double>(sim) * 1000.0) / 1000.0) < 1e-6;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(p * static_cast<double>(values.size())))];
}

template <class Msg>
std::vector<Msg> messages(const std::deque<test::Received<Msg>>& received) {
  std::vector<Msg> out;
  for (const auto& r : received) {
    out.push_back(r.msg);
  }
  return out;
}

Pose2 pose_of(const odometry_t& o) {
  return {o.x, o.y, o.theta};
}

// SIM_ODOMETRY at `utime`, interpolated; false outside the track.
bool sim_pose_at(const std::vector<odometry_t>& track, int64_t utime, Pose2* pose) {
  const auto it =
      std::lower_bound(track.begin(), track.end(), utime, [](const odometry_t& o, int64_t t) { return o.utime < t; });
  if (it == track.begin() || it == track.end()) {
    return false;
  }
  const odometry_t& a = *(it - 1);
  const odometry_t& b = *it;
  *pose = interpolate(pose_of(a), pose_of(b),
                      static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime));
  return true;
}

TEST(SimThroughDrivers, LidarAndOdometryAreTheSimulatedOnes) {
  const std::string url = test::unique_lcm_url(41);
  test::LcmTestBus bus(url);
  const auto& sim_lidar = bus.collect<laser_scan_t>("SIM_LIDAR");
  const auto& lidar = bus.collect<laser_scan_t>("LIDAR");
  const auto& sim_odometry_in = bus.collect<odometry_t>("SIM_ODOMETRY");
  const auto& odometry_in = bus.collect<odometry_t>("ODOMETRY");
  const auto& sim_encoders_in = bus.collect<wheel_encoders_t>("SIM_WHEEL_ENCODERS");
  const auto& encoders_in = bus.collect<wheel_encoders_t>("WHEEL_ENCODERS");
  const auto& status = bus.collect<process_status_t>("PROCESS_STATUS");
  int port = 0;
  auto urg_sim = test::start_urg_sim({"--source-channel", "SIM_LIDAR", "--lcm-url", url, "--drift-ppm", "50"}, &port);
  const std::string link = test::temp_path("sim_drivers_tfrog");
  auto tfrog_sim = test::start_tfrog_sim(link, {"--source-channel", "SIM_WHEEL_ENCODERS", "--lcm-url", url});
  auto urg = test::start_urg(url, port, {}, "config/urg_sim.yaml");
  auto wheels = test::start_wheels(url, link, "config/wheels_sim.yaml");
  // Both drivers up: the board streams, the sensor answered (it has no scans to send yet).
  ASSERT_TRUE(bus.pump_until(
      [&] {
        return odometry_in.size() >= 20 && std::any_of(status.begin(), status.end(), [](const auto& s) {
                 return s.msg.process == "slamer-urg" && s.msg.message.find("URM-40LC-EW") != std::string::npos;
               });
      },
      10.0))
      << urg->stderr_text() << wheels->stderr_text();

  const TempFile world{write_world()};
  test::ChildProcess sim(test::binary_path("slamer-sim"),
                         {"--world", world.path, "--config", std::string(SLAMER_SOURCE_DIR "/config/sim_drivers.yaml"),
                          "--seed", "1", "--speed", "1", "--lcm-url", url});
  ASSERT_TRUE(bus.pump_until([&] { return !sim.running(); }, 40.0)) << sim.stderr_text();
  ASSERT_EQ(sim.wait(1.0), 0) << sim.stderr_text();
  bus.pump_for(0.5);
  const std::vector<laser_scan_t> sim_scans = messages(sim_lidar), scans = messages(lidar);
  const std::vector<odometry_t> sim_odometry = messages(sim_odometry_in), odometry = messages(odometry_in);
  const std::vector<wheel_encoders_t> sim_encoders = messages(sim_encoders_in), encoders = messages(encoders_in);
  ASSERT_GT(sim_scans.size(), 400u) << sim.stderr_text();
  ASSERT_FALSE(scans.empty()) << urg->stderr_text() << urg_sim->stderr_text();

  // Scans: every simulated one from 0.5 s after the driver's first on, exactly once.
  const int64_t settled = scans.front().utime + 500000;
  std::vector<double> offsets_us;
  std::size_t next = 0, compared = 0, non_finite = 0;
  int64_t first_compared = 0;
  for (const laser_scan_t& s : sim_scans) {
    if (s.utime < settled) {
      continue;
    }
    while (next < scans.size() && scans[next].utime < s.utime - 12500) {
      ++next;  // a driver scan before this simulated one that matched none: counted below
    }
    int matches = 0;
    for (std::size_t j = next; j < scans.size() && scans[j].utime <= s.utime + 12500; ++j) {
      ++matches;
    }
    ASSERT_EQ(matches, 1) << "simulated scan seq " << s.seq << " is on LIDAR " << matches << " times\n"
                          << urg->stderr_text();
    const laser_scan_t& d = scans[next];
    first_compared = compared == 0 ? s.utime : first_compared;
    offsets_us.push_back(static_cast<double>(std::llabs(d.utime - s.utime)));
    ASSERT_EQ(d.nranges, s.nranges);
    EXPECT_NEAR(d.angle_min, s.angle_min, 1e-9);
    EXPECT_NEAR(d.angle_increment, s.angle_increment, 1e-12);
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
      ASSERT_TRUE(same_range(d.ranges[i], s.ranges[i]))
          << "scan " << s.seq << " beam " << i << ": LIDAR " << d.ranges[i] << ", SIM_LIDAR " << s.ranges[i];
      non_finite += std::isfinite(s.ranges[i]) ? 0 : 1;
    }
    ++compared;
    ++next;
  }
  const std::size_t driver_scans =
      static_cast<std::size_t>(std::count_if(scans.begin(), scans.end(), [&](const laser_scan_t& d) {
        return d.utime >= first_compared - 12500 && d.utime <= sim_scans.back().utime + 12500;
      }));
  EXPECT_EQ(driver_scans, compared) << "LIDAR has scans that are no simulated one";
  ASSERT_GT(compared, 400u);
  EXPECT_GT(non_finite, 0u);  // the classes were compared too (dropouts, no return)
  const double p50 = percentile(offsets_us, 0.5), p99 = percentile(offsets_us, 0.99);
  const double worst = *std::max_element(offsets_us.begin(), offsets_us.end());
  std::cout << "scans compared " << compared << ": |utime - sim utime| p50 " << p50 << " us, p99 " << p99 << " us, max "
            << worst << " us\n";
  EXPECT_LT(p99, 1000.0);
  EXPECT_LT(worst, 2000.0);

  // Odometry: both integrate the same wheel counts with the same .param, so
  // the driver's pose at its counts is the simulator's pose at those counts
  // (between two simulated samples the emulator ramps the counts linearly).
  // Matched on counts, not time: a starved emulator shifts the driver's frame
  // times, never its counts.
  ASSERT_GT(sim_odometry.size(), 1000u);
  ASSERT_EQ(sim_odometry.size(), sim_encoders.size());
  ASSERT_FALSE(encoders.empty());
  std::map<int64_t, const wheel_encoders_t*> driver_counts;  // by utime: one ODOMETRY and WHEEL_ENCODERS per frame
  for (const wheel_encoders_t& e : encoders) {
    driver_counts[e.utime] = &e;
  }
  const int64_t zero_left = encoders.front().ticks[0] - sim_encoders.front().ticks[0];
  const int64_t zero_right = encoders.front().ticks[1] - sim_encoders.front().ticks[1];
  double max_position = 0, max_heading = 0;
  std::size_t k = 0, matched = 0;
  for (const odometry_t& o : odometry) {
    const auto found = driver_counts.find(o.utime);
    if (found == driver_counts.end()) {
      continue;  // its WHEEL_ENCODERS twin was not received
    }
    const double left = static_cast<double>(found->second->ticks[0] - zero_left);
    const double right = static_cast<double>(found->second->ticks[1] - zero_right);
    // The simulated step (k, k + 1) whose counts bracket the driver's, searched forward.
    double best = INFINITY, fraction = 0;
    std::size_t best_k = k;
    for (std::size_t j = k; j + 1 < sim_encoders.size() && j < k + 400; ++j) {
      const double l0 = static_cast<double>(sim_encoders[j].ticks[0]),
                   l1 = static_cast<double>(sim_encoders[j + 1].ticks[0]);
      const double r0 = static_cast<double>(sim_encoders[j].ticks[1]),
                   r1 = static_cast<double>(sim_encoders[j + 1].ticks[1]);
      const double span = std::max(std::fabs(l1 - l0), std::fabs(r1 - r0));
      const double f = span > 0 ? std::clamp((std::fabs(l1 - l0) >= std::fabs(r1 - r0) ? (left - l0) / (l1 - l0)
                                                                                       : (right - r0) / (r1 - r0)),
                                             0.0, 1.0)
                                : 0.0;
      const double miss = std::fabs(left - (l0 + f * (l1 - l0))) + std::fabs(right - (r0 + f * (r1 - r0)));
      if (miss < best) {
        best = miss, fraction = f, best_k = j;
      }
      if (best == 0 && span > 0) {
        break;
      }
    }
    if (best > 2.0) {
      continue;  // counts the simulator never had: a frame from before the simulator started
    }
    k = best_k;
    const Pose2 p = interpolate(pose_of(sim_odometry[k]), pose_of(sim_odometry[k + 1]), fraction);
    max_position = std::max(max_position, std::hypot(o.x - p.x, o.y - p.y));
    max_heading = std::max(max_heading, std::fabs(angle_diff(o.theta, p.theta)));
    ++matched;
  }
  // The delay of the driver's track against the simulator's (a figure, not checked).
  int best_lag_ms = -1;
  double best_mean = INFINITY;
  for (int lag_ms = 0; lag_ms <= 60; ++lag_ms) {
    double sum = 0;
    int n = 0;
    for (const odometry_t& o : odometry) {
      Pose2 p;
      if (sim_pose_at(sim_odometry, o.utime - lag_ms * 1000, &p)) {
        sum += std::hypot(o.x - p.x, o.y - p.y);
        ++n;
      }
    }
    if (n > 1000 && sum / n < best_mean) {
      best_mean = sum / n;
      best_lag_ms = lag_ms;
    }
  }
  const odometry_t& end = odometry.back();
  const odometry_t& sim_end = sim_odometry.back();
  const double end_position = std::hypot(end.x - sim_end.x, end.y - sim_end.y);
  const double end_heading = std::fabs(angle_diff(end.theta, sim_end.theta));
  std::cout << "odometry: " << matched << " of " << odometry.size() << " poses matched on counts: max "
            << max_position * 1000 << " mm / " << max_heading * 180 / M_PI << " deg; delay " << best_lag_ms
            << " ms (mean " << best_mean * 1000 << " mm off at that delay); at the end " << end_position * 1000
            << " mm / " << end_heading * 180 / M_PI << " deg after " << std::hypot(sim_end.x, sim_end.y) << " m\n";
  std::string wheels_status;
  for (const auto& st : status) {
    wheels_status = st.msg.process == "slamer-wheels" ? st.msg.message : wheels_status;
  }
  const std::string why = "slamer-wheels: " + wheels_status + "\n" + wheels->stderr_text() + "slamer-tfrog-sim:\n" +
                          tfrog_sim->stdout_text() + tfrog_sim->stderr_text();
  EXPECT_GT(matched, odometry.size() / 2) << why;
  EXPECT_LT(max_position, 0.001) << why;
  EXPECT_LT(max_heading, 0.05 * M_PI / 180) << why;
  EXPECT_LT(end_position, 0.001) << why;  // the same whole counts: encoder quantization only
  EXPECT_LT(end_heading, 0.05 * M_PI / 180) << why;
}

}  // namespace
}  // namespace slamer

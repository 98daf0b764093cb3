// The simulated i-Cart mini through the real drivers under slamer-launch
// (as config/launch/icart_mini_sim.yaml, on the small world): `kill -9` of
// the wheel driver and then of the URG driver. Supervisor restarts each; the
// localizer, which keeps running, says DEGRADED while that input is missing,
// and OK again once it is back, tracking on without LOST, without a reset.
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "test/launch/launch_listener.hpp"

namespace slamer {
namespace {

namespace fs = std::filesystem;
const std::string kSourceDir = SLAMER_SOURCE_DIR;
using test::Listener;

// The localizer's first status at or after `from` in `state` whose message has `text`; -1 if none.
double localizer_state_after(const Listener& bus, double from, int8_t state, const std::string& text) {
  for (const Listener::StatusSeen& s : bus.statuses) {
    if (s.process == "slamer-localizer" && s.at >= from && s.state == state &&
        s.message.find(text) != std::string::npos) {
      return s.at;
    }
  }
  return -1.0;
}

// What the stack's processes logged, for a failure message: the supervisor's spawns and exits,
// and the logs of the two processes downstream of the drivers.
std::string stack_logs(const std::string& dir) {
  std::string text;
  for (const char* name : {"supervisord", "recognizer", "localizer"}) {
    text += std::string("--- ") + name + ".log\n" + test::read_file(dir + "/log/" + name + ".log");
  }
  return text;
}

TEST(SlamerLaunch, Kill9OfADriverIsAGapTheLocalizerReportsAsDegradedAndRidesOut) {
  const std::string dir = test::temp_dir();
  const std::string url = test::unique_lcm_url(73);
  const std::string port = std::to_string(test::free_tcp_port());
  const std::string config = kSourceDir + "/config/";
  // The shipped input timeouts; statuses at 5 Hz only to keep the test short.
  std::ofstream(dir + "/localizer.yaml") << "map: " << config << "maps/small_room/map.yaml\nrobot: " << config
                                         << "robots/icart_mini.yaml\nparticles_out: 0\nprocess: {status_period: 0.2}\n"
                                         << "localizer: {particles: 300, initial_pose: [1.5, 3.0, 0.0]}\n";
  std::ofstream(dir + "/launch.yaml")
      << "lcm_url: \"" << url << "\"\nlog_dir: " << dir << "/log\nrun_dir: " << dir << "/run\nprocesses:\n"
      << "  - {name: urg-sim, program: slamer-urg-sim, args: [--source-channel, SIM_LIDAR, --port, '" << port
      << "'], start_seconds: 1}\n"
      << "  - {name: tfrog-sim, program: slamer-tfrog-sim, args: [--source-channel, SIM_WHEEL_ENCODERS, --link, "
      << "'${run_dir}/tfrog', --robot, " << config << "robots/icart-mini.param], start_seconds: 1}\n"
      << "  - {name: urg, program: slamer-urg, config: " << config << "urg_sim.yaml, args: [--port, '" << port
      << "'], group: 1, start_seconds: 1}\n"
      << "  - {name: wheels, program: slamer-wheels, config: " << config
      << "wheels_sim.yaml, args: [--device, '${run_dir}/tfrog'], group: 1, start_seconds: 1}\n"
      << "  - {name: recognizer, program: slamer-recognizer, config: " << config
      << "recognizer.yaml, group: 2, start_seconds: 1}\n"
      << "  - {name: localizer, program: slamer-localizer, config: localizer.yaml, group: 2, start_seconds: 1}\n"
      << "  - {name: sim, program: slamer-sim, config: " << config << "sim_drivers.yaml, args: [--world, " << config
      << "worlds/small_room.yaml, --laps, '4'], group: 3, respawn: false, start_seconds: 1}\n";
  Listener bus(url);
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});

  const auto tracking_since = [&](double from) {
    std::size_t n = 0;
    for (const auto& [at, pose] : bus.poses) {
      n += at >= from && pose.status == pose_estimate_t::OK && test::error_to_truth(pose, bus.truth) < 0.3;
    }
    return n;
  };
  ASSERT_TRUE(bus.until(60.0, [&] { return tracking_since(0.0) >= 40; })) << "the stack did not come up and track\n"
                                                                          << launch.stderr_text();
  ASSERT_EQ(bus.pids["slamer-localizer"].size(), 1u);
  const int32_t localizer_pid = *bus.pids["slamer-localizer"].begin();
  const std::size_t poses_before = bus.poses.size();

  struct Gap {
    const char* driver;
    const char* missing;  // in the localizer's DEGRADED message
  };
  // A driver's stream is back 0.1-0.6 s after the kill, about the input timeouts (0.5 s for
  // odometry, 2 s for scans): the localizer says "no ODOMETRY for ..." if the gap was longer,
  // and sees the restart in the stream's seq in any case; the next PROCESS_STATUS says so.
  for (const Gap gap : {Gap{"slamer-wheels", "ODOMETRY"}, Gap{"slamer-urg", "LIDAR's driver restarted"}}) {
    ASSERT_TRUE(bus.until(5.0, [&] { return bus.pids[gap.driver].size() == 1; })) << gap.driver;
    ASSERT_EQ(::kill(*bus.pids[gap.driver].begin(), SIGKILL), 0);
    const double killed_at = test::since(bus.t0);
    ASSERT_TRUE(bus.until(
        10.0, [&] { return localizer_state_after(bus, killed_at, process_status_t::DEGRADED, gap.missing) > 0.0; }))
        << "the localizer did not report the gap of " << gap.driver << "\n"
        << stack_logs(dir);
    const double degraded_at = localizer_state_after(bus, killed_at, process_status_t::DEGRADED, gap.missing);
    ASSERT_TRUE(bus.until(20.0,
                          [&] {
                            return bus.pids[gap.driver].size() == 2 &&
                                   localizer_state_after(bus, degraded_at, process_status_t::OK, "") > 0.0 &&
                                   tracking_since(localizer_state_after(bus, degraded_at, process_status_t::OK, "")) >=
                                       20;
                          }))
        << gap.driver << " came back but the localizer did not track OK again\n"
        << stack_logs(dir);
    const std::vector<double>& stream = gap.driver == std::string("slamer-urg") ? bus.lidar : bus.odometry;
    std::printf(
        "[ measured ] kill -9 of %s: its stream back after %.2f s; the localizer DEGRADED after %.2f s, OK again "
        "after %.2f s\n",
        gap.driver, test::first_after(stream, killed_at + 0.1) - killed_at, degraded_at - killed_at,
        localizer_state_after(bus, degraded_at, process_status_t::OK, "") - killed_at);
  }
  // The localizer rode both gaps out: the same process, no pose LOST and none far off.
  EXPECT_EQ(bus.pids["slamer-localizer"], std::set<int32_t>{localizer_pid});
  double worst = 0.0;
  for (std::size_t i = poses_before; i < bus.poses.size(); ++i) {
    EXPECT_NE(bus.poses[i].second.status, pose_estimate_t::LOST) << "pose " << i;
    worst = std::max(worst, test::error_to_truth(bus.poses[i].second, bus.truth));
  }
  EXPECT_LT(worst, 0.5);
  std::printf("[ measured ] %zu poses through both gaps, worst %.3f m off\n", bus.poses.size() - poses_before, worst);
  launch.signal(SIGTERM);
  EXPECT_EQ(launch.wait(30.0), std::optional<int>(0)) << launch.stderr_text();
  // Its closing line counts its resets (time going back, a new start): none. Each restart was seen.
  const std::string log = test::read_file(dir + "/log/localizer.log");
  EXPECT_NE(log.find(" 0 resets;"), std::string::npos) << log;
  EXPECT_EQ(test::count(log, "ODOMETRY's driver restarted (seq "), 1u) << log;
  EXPECT_EQ(test::count(log, "LIDAR's driver restarted (seq "), 1u) << log;
  const std::string spawns = test::read_file(dir + "/log/supervisord.log");
  EXPECT_EQ(test::count(spawns, "spawned: 'localizer'"), 1u) << spawns;
  EXPECT_EQ(test::count(spawns, "spawned: 'urg'"), 2u) << spawns;
  EXPECT_EQ(test::count(spawns, "spawned: 'wheels'"), 2u) << spawns;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slamer

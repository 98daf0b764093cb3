// slamer-launch with the real supervisord and real programs over loopback LCM:
// a simulated stack comes up in order and publishes; `kill -9` of the
// localizer is answered by supervisor with a restart that resumes from the
// pose file and gets back to OK, while nothing else restarts; SIGTERM stops
// every process and exits 0; a required process's end ends the launch; a
// crashing one is retried with backoff, then FATAL; --check lists problems.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>

#include "test/launch/launch_listener.hpp"

namespace slamer {
namespace {

namespace fs = std::filesystem;
const std::string kSource = SLAMER_SOURCE_DIR;
using test::alive;
using test::Clock;
using test::count;
using test::error_to_truth;
using test::first_after;
using test::free_tcp_port;
using test::Listener;
using test::since;
using test::supervisord_pid;
using test::temp_dir;

TEST(SlamerLaunch, SimulatedStackStartsInOrderSurvivesKill9AndStopsOnSigterm) {
  const std::string dir = temp_dir();
  const std::string url = test::unique_lcm_url(71);
  const std::string pose_file = dir + "/pose.yaml";
  std::ofstream(dir + "/localizer.yaml") << "map: " << kSource << "/config/maps/small_room/map.yaml\nrobot: " << kSource
                                         << "/config/robots/icart_mini.yaml\npose_file: " << pose_file
                                         << "\npose_save_period: 0.2\nparticles_out: 0\n"
                                         << "localizer: {particles: 300, initial_pose: [1.5, 3.0, 0.0]}\n";
  std::ofstream(dir + "/launch.yaml")
      << "lcm_url: \"" << url << "\"\nlog_dir: " << dir << "/log\nrun_dir: " << dir << "/run\nprocesses:\n"
      << "  - {name: recognizer, program: slamer-recognizer, config: " << kSource
      << "/config/recognizer.yaml, start_seconds: 1}\n"
      << "  - {name: localizer, program: slamer-localizer, config: localizer.yaml, start_seconds: 1}\n"
      << "  - {name: sim, program: slamer-sim, config: " << kSource << "/config/sim.yaml, args: [--world, " << kSource
      << "/config/worlds/small_room.yaml], group: 1, respawn: false, start_seconds: 1}\n";
  Listener bus(url);
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});
  const auto start = Clock::now();

  // Everything up and publishing: poses near the truth, line objects.
  ASSERT_TRUE(bus.until(30.0, [&] { return bus.poses.size() >= 40 && bus.line_objects >= 40; }))
      << launch.stderr_text();
  const double up_s = since(start);
  for (const char* name : {"slamer-recognizer", "slamer-localizer", "slamer-sim", "slamer-launch"}) {
    EXPECT_EQ(bus.pids[name].size(), 1u) << name;
  }
  EXPECT_LT(error_to_truth(bus.poses.back().second, bus.truth), 0.3);
  // The sim (group 1) was spawned only once the localizer (group 0) was RUNNING.
  const std::string supervisor_log = test::read_file(dir + "/log/supervisord.log");
  const std::size_t localizer_up = supervisor_log.find("success: localizer entered RUNNING");
  const std::size_t sim_spawned = supervisor_log.find("spawned: 'sim'");
  ASSERT_NE(sim_spawned, std::string::npos) << supervisor_log;
  EXPECT_LT(localizer_up, sim_spawned) << supervisor_log;
  EXPECT_TRUE(fs::exists(dir + "/log/localizer.log"));

  // kill -9 of the localizer once the robot is 2.5 m from the configured start: supervisor
  // restarts it; it resumes from its pose file, not from the start.
  ASSERT_TRUE(bus.until(20.0, [&] { return !bus.truth.empty() && bus.truth.back().x > 4.0; }));
  const int32_t old_pid = *bus.pids["slamer-localizer"].begin();
  ASSERT_TRUE(fs::exists(pose_file));
  ASSERT_EQ(::kill(old_pid, SIGKILL), 0);
  const double killed_at = since(bus.t0);
  const int64_t killed_utime =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count();
  ASSERT_TRUE(bus.until(15.0, [&] { return bus.pids["slamer-localizer"].size() == 2; })) << launch.stderr_text();
  // Its first poses are not LOST and it reaches OK within 5 s of its first pose, near the truth.
  const std::size_t first_after = [&] {
    std::size_t i = 0;
    // Poses of scans taken after the kill come from the new process (older ones may still be in flight).
    while (i < bus.poses.size() && bus.poses[i].second.utime <= killed_utime) {
      ++i;
    }
    return i;
  }();
  ASSERT_TRUE(bus.until(15.0, [&] { return bus.poses.size() > first_after + 5; }));
  const double resumed_at = bus.poses[first_after].first;
  EXPECT_NE(bus.poses[first_after].second.status, pose_estimate_t::LOST);
  EXPECT_NE(bus.poses[first_after].second.status, pose_estimate_t::INITIALIZING);
  EXPECT_LT(error_to_truth(bus.poses[first_after].second, bus.truth), 1.0);  // the robot drove on meanwhile
  EXPECT_GT(bus.poses[first_after].second.x, 3.5);                           // the configured start is x = 1.5
  bool ok = false;
  ASSERT_TRUE(bus.until(8.0, [&] {
    for (std::size_t i = first_after; i < bus.poses.size() && !ok; ++i) {
      ok = bus.poses[i].second.status == pose_estimate_t::OK && bus.poses[i].first - resumed_at <= 5.0 &&
           error_to_truth(bus.poses[i].second, bus.truth) < 0.3;
    }
    return ok;
  })) << "no OK pose within 5 s of the restart";
  double ok_at = 0.0;
  for (std::size_t i = first_after; i < bus.poses.size() && ok_at == 0.0; ++i) {
    ok_at = bus.poses[i].second.status == pose_estimate_t::OK ? bus.poses[i].first : 0.0;
  }
  for (std::size_t i = first_after; i < bus.poses.size(); ++i) {
    EXPECT_NE(bus.poses[i].second.status, pose_estimate_t::LOST) << "pose " << i - first_after << " after restart";
  }
  std::printf(
      "[ measured ] up %.2f s after start; killed at %.2f s: first pose %.2f s later (status %d, %.3f m off), OK "
      "%.2f s after the kill\n",
      up_s, killed_at, resumed_at - killed_at, bus.poses[first_after].second.status,
      error_to_truth(bus.poses[first_after].second, bus.truth), ok_at - killed_at);
  bus.until(1.5, [] { return false; });
  // Nothing else restarted.
  EXPECT_EQ(bus.pids["slamer-recognizer"].size(), 1u);
  EXPECT_EQ(bus.pids["slamer-sim"].size(), 1u);
  EXPECT_EQ(bus.pids["slamer-launch"].size(), 1u);
  const std::string spawns = test::read_file(dir + "/log/supervisord.log");
  EXPECT_EQ(count(spawns, "spawned: 'localizer'"), 2u) << spawns;
  EXPECT_EQ(count(spawns, "spawned: 'recognizer'"), 1u) << spawns;
  EXPECT_EQ(count(spawns, "spawned: 'sim'"), 1u) << spawns;

  // SIGTERM: every process gone, supervisord too, exit 0.
  std::vector<int64_t> pids{supervisord_pid(launch.stderr_text())};
  for (const char* name : {"slamer-recognizer", "slamer-localizer", "slamer-sim"}) {
    pids.insert(pids.end(), bus.pids[name].begin(), bus.pids[name].end());
  }
  ASSERT_GT(pids[0], 0) << launch.stderr_text();
  const auto stop = Clock::now();
  launch.signal(SIGTERM);
  const auto code = launch.wait(30.0);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0) << launch.stderr_text();
  std::printf("[ measured ] stopped %.2f s after SIGTERM\n", since(stop));
  for (const int64_t pid : pids) {
    EXPECT_FALSE(alive(pid)) << "pid " << pid << " is still running";
  }
  EXPECT_NE(launch.stderr_text().find("stopping sim"), std::string::npos);
  // Reverse order: the sim (group 1) stopped before the localizer (group 0).
  const std::string text = launch.stderr_text();
  EXPECT_LT(text.find("stopping sim"), text.find("stopping recognizer")) << text;
  fs::remove_all(dir);
}

// The real drivers against their device emulators: kill -9 of either driver is
// answered by a restart and its stream resumes; nothing else restarts.
TEST(SlamerLaunch, Kill9OfADriverRestartsOnlyThatDriver) {
  const std::string dir = temp_dir();
  const std::string url = test::unique_lcm_url(72);
  const std::string port = std::to_string(free_tcp_port());
  std::ofstream(dir + "/launch.yaml")
      << "lcm_url: \"" << url << "\"\nlog_dir: " << dir << "/log\nrun_dir: " << dir << "/run\nprocesses:\n"
      << "  - {name: urg-sim, program: slamer-urg-sim, args: [--port, '" << port
      << "'], lcm: false, start_seconds: 1}\n"
      << "  - {name: tfrog-sim, program: slamer-tfrog-sim, args: [--link, '${run_dir}/tfrog', --robot, " << kSource
      << "/config/robots/icart-mini.param, --path, '0.2,0,120'], start_seconds: 1}\n"
      << "  - {name: urg, program: slamer-urg, config: " << kSource
      << "/config/urg.yaml, args: [--host, 127.0.0.1, --port, '" << port << "'], group: 1, start_seconds: 1}\n"
      << "  - {name: wheels, program: slamer-wheels, config: " << kSource
      << "/config/wheels.yaml, args: [--device, '${run_dir}/tfrog'], group: 1, start_seconds: 1}\n";
  Listener bus(url);
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});
  ASSERT_TRUE(bus.until(20.0, [&] { return bus.lidar.size() >= 20 && bus.odometry.size() >= 50; }))
      << launch.stderr_text();
  for (const std::string driver : {"slamer-urg", "slamer-wheels"}) {
    ASSERT_TRUE(bus.until(5.0, [&] { return bus.pids[driver].size() == 1; })) << driver;
    ASSERT_EQ(::kill(*bus.pids[driver].begin(), SIGKILL), 0);
    const double killed_at = since(bus.t0);
    const std::vector<double>& stream = driver == "slamer-urg" ? bus.lidar : bus.odometry;
    ASSERT_TRUE(
        bus.until(15.0, [&] { return bus.pids[driver].size() == 2 && first_after(stream, killed_at + 0.3) > 0; }))
        << driver << " did not come back\n"
        << launch.stderr_text();
    std::printf("[ measured ] kill -9 of %s: its stream back %.2f s later\n", driver.c_str(),
                first_after(stream, killed_at + 0.3) - killed_at);
  }
  const std::string log = test::read_file(dir + "/log/supervisord.log");
  EXPECT_EQ(count(log, "spawned: 'urg-sim'"), 1u) << log;
  EXPECT_EQ(count(log, "spawned: 'tfrog-sim'"), 1u) << log;
  EXPECT_EQ(count(log, "spawned: 'urg'"), 2u) << log;
  EXPECT_EQ(count(log, "spawned: 'wheels'"), 2u) << log;
  launch.signal(SIGTERM);
  EXPECT_EQ(launch.wait(30.0), std::optional<int>(0)) << launch.stderr_text();
  fs::remove_all(dir);
}

// Launch files of plain programs (not on LCM): how the launch ends.
struct Ended {
  int code = -1;
  std::string log;             // slamer-launch's
  std::string supervisor_log;  // supervisord's
};
Ended run_until_it_ends(const std::string& processes) {
  const std::string dir = temp_dir();
  std::ofstream(dir + "/launch.yaml") << "log_dir: " << dir << "/log\nprocesses:\n" << processes;
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});
  const auto code = launch.wait(40.0);
  Ended ended{code.value_or(-1), launch.stderr_text(), test::read_file(dir + "/log/supervisord.log")};
  fs::remove_all(dir);
  return ended;
}

TEST(SlamerLaunch, ARequiredProcessEndsTheLaunchWithItsOutcome) {
  const Ended clean = run_until_it_ends(
      "  - {name: idle, program: /bin/sleep, args: ['30'], lcm: false, start_seconds: 0}\n"
      "  - {name: job, program: /bin/sleep, args: ['1'], lcm: false, required: true, respawn: false, group: 1,"
      " start_seconds: 0}\n");
  EXPECT_EQ(clean.code, 0) << clean.log;
  EXPECT_NE(clean.log.find("required process 'job' finished"), std::string::npos) << clean.log;
  EXPECT_NE(clean.log.find("stopping idle"), std::string::npos) << clean.log;

  const Ended failed = run_until_it_ends(
      "  - {name: job, program: /bin/sh, args: [-c, 'sleep 0.5; exit 3'], lcm: false, required: true,"
      " respawn: false, start_seconds: 0}\n");
  EXPECT_EQ(failed.code, 1) << failed.log;
  EXPECT_NE(failed.log.find("ended for good (EXITED)"), std::string::npos) << failed.log;
}

TEST(SlamerLaunch, ACrashingProcessIsRetriedWithBackoffThenFatal) {
  // Dies before start_seconds every time: supervisor's BACKOFF, 2 retries, FATAL.
  const Ended ended = run_until_it_ends(
      "  - {name: crash, program: /bin/sh, args: [-c, 'exit 1'], lcm: false, required: true, start_seconds: 1,"
      " start_retries: 2}\n");
  EXPECT_EQ(ended.code, 1) << ended.log;
  std::size_t spawns = 0;
  for (std::size_t at = ended.supervisor_log.find("spawned: 'crash'"); at != std::string::npos;
       at = ended.supervisor_log.find("spawned: 'crash'", at + 1)) {
    ++spawns;
  }
  EXPECT_EQ(spawns, 3u) << ended.supervisor_log;  // the start and 2 retries
  EXPECT_NE(ended.supervisor_log.find("gave up: crash entered FATAL state"), std::string::npos);
  EXPECT_NE(ended.log.find("-> FATAL"), std::string::npos) << ended.log;
}

// Ctrl-C (SIGINT to slamer-launch alone, as a terminal's is once supervisord has its own session).
TEST(SlamerLaunch, SigintStopsEveryProcessAndExitsZero) {
  const std::string dir = temp_dir();
  std::ofstream(dir + "/launch.yaml")
      << "log_dir: " << dir << "/log\nrun_dir: " << dir << "/run\nprocesses:\n"
      << "  - {name: a, program: /bin/sleep, args: ['60'], lcm: false, start_seconds: 0}\n"
      << "  - {name: b, program: /bin/sh, args: [-c, 'trap \"\" TERM; sleep 60'], lcm: false, start_seconds: 0,"
      << " group: 1, stop_timeout: 1}\n";
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});
  const auto start = Clock::now();
  while (launch.stderr_text().find("every group is up") == std::string::npos && since(start) < 20.0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_NE(launch.stderr_text().find("every group is up"), std::string::npos) << launch.stderr_text();
  std::vector<int64_t> pids{supervisord_pid(launch.stderr_text())};
  const std::string log = test::read_file(dir + "/log/supervisord.log");
  for (const std::string name : {"'a' with pid ", "'b' with pid "}) {
    const std::size_t at = log.find(name);
    ASSERT_NE(at, std::string::npos) << log;
    pids.push_back(std::atoll(log.c_str() + at + name.size()));
  }
  // A second launch on the same run directory is refused: it would drive the first one's supervisord.
  test::ChildProcess second(test::binary_path("slamer-launch"), {dir + "/launch.yaml"});
  EXPECT_EQ(second.wait(20.0), std::optional<int>(1));
  EXPECT_NE(second.stderr_text().find("another slamer-launch with this run directory?"), std::string::npos)
      << second.stderr_text();
  launch.signal(SIGINT);
  EXPECT_EQ(launch.wait(20.0), std::optional<int>(0)) << launch.stderr_text();
  for (const int64_t pid : pids) {
    EXPECT_FALSE(alive(pid)) << "pid " << pid << " is still running";
  }
  // b ignores SIGTERM: supervisor's SIGKILL after its stop_timeout; then a, in reverse order.
  const std::string text = launch.stderr_text();
  EXPECT_LT(text.find("stopping b"), text.find("stopping a")) << text;
  EXPECT_NE(test::read_file(dir + "/log/supervisord.log").find("killing 'b'"), std::string::npos);
  fs::remove_all(dir);
}

TEST(SlamerLaunch, CheckListsEveryProblemAndStartsNothing) {
  const std::string dir = temp_dir();
  std::ofstream(dir + "/recognizer.yaml") << "channels: {lidar: LIDAR, bogus: 1}\n";
  std::ofstream(dir + "/bad.yaml") << "lcm_url: x\nlog_dirr: y\nprocesses:\n"
                                   << "  - {name: rec, program: slamer-recognizer, config: recognizer.yaml}\n"
                                   << "  - {name: rec, program: slamer-nothing}\n";
  test::ChildProcess check(test::binary_path("slamer-launch"), {"--check", dir + "/bad.yaml"});
  ASSERT_EQ(check.wait(30.0), std::optional<int>(1));
  std::istringstream lines(check.stdout_text());
  std::vector<std::string> problems;
  for (std::string line; std::getline(lines, line);) {
    problems.push_back(line);
  }
  ASSERT_EQ(problems.size(), 4u) << check.stdout_text();
  EXPECT_EQ(problems[0].rfind(dir + "/bad.yaml:2: key 'log_dirr': unknown key", 0), 0u) << problems[0];
  EXPECT_EQ(problems[1].rfind(dir + "/bad.yaml:5: key 'processes[1].name': duplicate name 'rec'", 0), 0u);
  EXPECT_EQ(problems[2].rfind(dir + "/recognizer.yaml:1: unknown key 'channels.bogus'", 0), 0u) << problems[2];
  EXPECT_EQ(problems[3].rfind(dir + "/bad.yaml:5: key 'processes[1].program': program 'slamer-nothing'", 0), 0u);
  EXPECT_FALSE(fs::exists(dir + "/slamer_logs"));  // started nothing

  // Started without --check, a bad file starts nothing either.
  test::ChildProcess launch(test::binary_path("slamer-launch"), {dir + "/bad.yaml"});
  ASSERT_EQ(launch.wait(30.0), std::optional<int>(1));
  EXPECT_NE(launch.stderr_text().find("4 problem(s), nothing started"), std::string::npos) << launch.stderr_text();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slamer

// Process-level tests: real programs talking LCM over UDP multicast on
// loopback, each test on its own port.
#include <gtest/gtest.h>
#include <signal.h>
#include <lcm/lcm-cpp.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <random>
#include <thread>

#include "common/process/decode.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/process_status_t.hpp"
#include "slamer/velocity_command_t.hpp"
#include "slamer/wheel_encoders_t.hpp"
#include "test/support/child_process.hpp"
#include "test/support/lcm_test_bus.hpp"

namespace slamer {
namespace {

using test::binary_path;
using test::ChildProcess;

template <class Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  return test::LcmTestBus::encode(msg);
}

laser_scan_t make_scan(int64_t seq) {
  laser_scan_t scan;
  scan.utime = 1'700'000'000'000'000 + seq;
  scan.sensor_utime = seq * 25'000;
  scan.seq = seq;
  scan.frame = "laser";
  scan.angle_min = -2.35619449;
  scan.angle_increment = 0.00436332313;
  scan.range_min = 0.1f;
  scan.range_max = 30.0f;
  scan.time_increment = 1.7e-5f;
  scan.scan_period = 0.025f;
  scan.nranges = 1081;
  scan.ranges.assign(1081, 2.5f);
  scan.ranges[3] = std::numeric_limits<float>::quiet_NaN();
  scan.nintensities = 0;
  return scan;
}

using Bus = test::LcmTestBus;

TEST(Processes, TwoProcessesExchangeMessagesOverMulticast) {
  const std::string url = test::unique_lcm_url(1);
  Bus bus(url);
  const auto* echoes = &bus.collect<laser_scan_t>("LIDAR_ECHO");
  ChildProcess echo(binary_path("slamer-test-echo"), {"--lcm-url", url});
  ChildProcess status(binary_path("slamer-status"),
                      {"--lcm-url", url, "--once", "3", "--expect", "slamer-test-echo", "--json"});

  int64_t seq = 0;
  ASSERT_TRUE(bus.pump_until([&] { return !echoes->empty(); }, 5.0, [&] { bus.publish("LIDAR", make_scan(++seq)); }))
      << "no echo; echo stderr:\n"
      << echo.stderr_text();
  const laser_scan_t& got = echoes->front().msg;
  EXPECT_GE(got.seq, 1);
  EXPECT_EQ(got.utime, 1'700'000'000'000'000 + got.seq);
  ASSERT_EQ(got.ranges.size(), 1081u);
  EXPECT_FLOAT_EQ(got.ranges[0], 2.5f);
  EXPECT_TRUE(std::isnan(got.ranges[3]));

  // slamer-status, a second real process, saw the echo process's PROCESS_STATUS.
  const std::optional<int> status_exit = status.wait(8.0);
  ASSERT_TRUE(status_exit.has_value()) << "slamer-status did not finish";
  EXPECT_EQ(*status_exit, 0) << status.stderr_text();
  const nlohmann::json json = nlohmann::json::parse(status.stdout_text());
  int64_t lidar_in = -1;
  for (const nlohmann::json& process : json.at("processes")) {
    for (const nlohmann::json& channel : process.at("channels")) {
      if (process.at("process") == "slamer-test-echo" && channel.at("channel") == "LIDAR" &&
          channel.at("direction") == "in") {
        lidar_in = channel.at("messages").get<int64_t>();
      }
    }
  }
  EXPECT_GE(lidar_in, 1) << json.dump();

  echo.signal(SIGTERM);
  const std::optional<int> echo_exit = echo.wait(3.0);
  ASSERT_TRUE(echo_exit.has_value()) << "slamer-test-echo ignored SIGTERM";
  EXPECT_EQ(*echo_exit, 0);
  EXPECT_NE(echo.stderr_text().find("received SIGTERM, stopping"), std::string::npos) << echo.stderr_text();
}

// Valid encodings of each subscribed channel's own type.
std::map<std::string, std::vector<uint8_t>> valid_messages() {
  odometry_t odometry{};
  wheel_encoders_t wheels{};
  wheels.source = "tfrog";
  wheels.nwheels = 2;
  wheels.ticks = {100, -200};
  line_objects_t objects{};
  objects.frame = "laser";
  objects.nclasses = 2;
  objects.class_names = {"door", "others"};
  objects.nobjects = 0;
  initial_pose_t initial{};
  velocity_command_t command{};
  return {{"LIDAR", encode(make_scan(7))},   {"ODOMETRY", encode(odometry)},    {"WHEEL_ENCODERS", encode(wheels)},
          {"LINE_OBJECTS", encode(objects)}, {"INITIAL_POSE", encode(initial)}, {"CMD_VEL", encode(command)}};
}

TEST(Processes, GarbageOnEveryChannelIsCountedAndSurvived) {
  const std::string url = test::unique_lcm_url(2);
  Bus bus(url);
  const auto* echoes = &bus.collect<laser_scan_t>("LIDAR_ECHO");
  const auto* statuses = &bus.collect<process_status_t>("PROCESS_STATUS");
  ChildProcess echo(binary_path("slamer-test-echo"), {"--lcm-url", url});
  ASSERT_TRUE(bus.pump_until([&] { return !echoes->empty(); }, 5.0, [&] { bus.publish("LIDAR", make_scan(1)); }))
      << echo.stderr_text();

  std::mt19937 rng(99);
  std::map<std::string, int> sent_bad;
  const auto valid = valid_messages();
  for (const auto& [channel, bytes] : valid) {
    std::vector<std::vector<uint8_t>> bad;
    bad.push_back({});                  // empty
    bad.push_back({0xde, 0xad, 0xbe});  // shorter than a fingerprint
    std::vector<uint8_t> noise(200);
    for (uint8_t& b : noise) {
      b = static_cast<uint8_t>(rng());
    }
    bad.push_back(noise);                                                          // garbage
    bad.push_back(channel == "LIDAR" ? valid.at("ODOMETRY") : valid.at("LIDAR"));  // another type
    bad.push_back(std::vector<uint8_t>(bytes.begin(), bytes.end() - 1));           // truncated
    std::vector<uint8_t> trailing = bytes;
    trailing.push_back(0);
    bad.push_back(trailing);  // trailing bytes
    for (const auto& message : bad) {
      bus.publish_raw(channel, message);
    }
    sent_bad[channel] = static_cast<int>(bad.size());
  }
  // A scan whose beam count claims two billion floats (would be an 8 GB resize).
  std::vector<uint8_t> forged = valid.at("LIDAR");
  const std::size_t count_offset = 74;
  forged[count_offset] = 0x7f;
  bus.publish_raw("LIDAR", forged);
  ++sent_bad["LIDAR"];

  // Still alive and still working.
  const std::size_t echoed_before = echoes->size();
  ASSERT_TRUE(bus.pump_until([&] { return echoes->size() > echoed_before; }, 5.0,
                             [&] { bus.publish("LIDAR", make_scan(1000)); }))
      << echo.stderr_text();
  EXPECT_TRUE(echo.running());

  // Its PROCESS_STATUS counts every bad message on the channel it came in on.
  const auto counted_all = [&] {
    for (const auto& [s, received_at] : *statuses) {
      if (s.process != "slamer-test-echo") {
        continue;
      }
      int matched = 0;
      for (const auto& c : s.channels) {
        const auto it = sent_bad.find(c.channel);
        if (it != sent_bad.end() && c.decode_errors == it->second) {
          ++matched;
        }
      }
      if (matched == static_cast<int>(sent_bad.size())) {
        return true;
      }
    }
    return false;
  };
  ASSERT_TRUE(bus.pump_until(counted_all, 4.0)) << "decode errors not counted per channel; stderr:\n"
                                                << echo.stderr_text();
  int total_bad = 0;
  for (const auto& [channel, n] : sent_bad) {
    total_bad += n;
  }
  EXPECT_EQ(statuses->back().msg.decode_errors, total_bad);

  echo.signal(SIGINT);
  ASSERT_EQ(echo.wait(3.0), std::optional<int>(0));
  // Logged as a few one-line summaries, not a line per bad message.
  const std::string log = echo.stderr_text();
  int summary_lines = 0;
  for (std::size_t at = log.find("decode error"); at != std::string::npos; at = log.find("decode error", at + 1)) {
    ++summary_lines;
  }
  EXPECT_GE(summary_lines, 1) << log;
  EXPECT_LE(summary_lines, 4) << log;
  EXPECT_NE(log.find("LIDAR"), std::string::npos);
}

TEST(Processes, BadConfigOrUrlExitsWithOneLine) {
  const auto run = [](const std::vector<std::string>& args) {
    ChildProcess child(binary_path("slamer-test-echo"), args);
    const std::optional<int> code = child.wait(5.0);
    return std::make_pair(code.value_or(-1), child.stderr_text());
  };
  auto [code, err] = run({"--config", "/nonexistent/echo.yaml"});
  EXPECT_EQ(code, 1);
  EXPECT_EQ(err, "slamer-test-echo: config error: /nonexistent/echo.yaml: cannot open: No such file or directory\n");

  const std::string path = std::string(SLAMER_BINARY_DIR "/echo_bad_key.yaml");
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("process:\n  status_period: 1.0\n  statsu_channel: X\n", f);
    std::fclose(f);
  }
  std::tie(code, err) = run({"--config", path});
  EXPECT_EQ(code, 1);
  EXPECT_EQ(err, "slamer-test-echo: config error: " + path + ":3: unknown key 'process.statsu_channel'\n");

  std::tie(code, err) = run({"--lcm-url", "nosuchprovider://x"});
  EXPECT_EQ(code, 1);
  EXPECT_NE(err.find("slamer-test-echo: error: cannot open LCM URL 'nosuchprovider://x'"), std::string::npos) << err;

  std::tie(code, err) = run({"--frobnicate"});
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err, "slamer-test-echo: error: unknown option '--frobnicate' (see --help)\n");

  ChildProcess help(binary_path("slamer-test-echo"), {"--help"});
  EXPECT_EQ(help.wait(5.0), std::optional<int>(0));
  EXPECT_NE(help.stdout_text().find("--lcm-url URL"), std::string::npos);
}

}  // namespace
}  // namespace slamer

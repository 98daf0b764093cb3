// End to end: the real slamer-urg against slamer-urg-sim on loopback (free
// ports), scans and PROCESS_STATUS read from LCM: geometry and ranges, damaged
// replies, the sensor refusing / dropping / going silent and coming back,
// SCIP 1.1, a geometry change after a reboot, the serial path over a pty.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <numbers>
#include <thread>

#include "common/process/decode.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/support/child_process.hpp"
#include "test/support/driver_processes.hpp"
#include "test/support/temp_dir.hpp"
#include "tools/urg_sim/sim_sensor.hpp"

namespace slamer {
namespace {

using Clock = std::chrono::steady_clock;

struct Bus {
  explicit Bus(const std::string& url) : lcm(url) {
    lcm.subscribeFunction("LIDAR", &Bus::on_scan, this);
    lcm.subscribeFunction("PROCESS_STATUS", &Bus::on_status, this);
  }
  static void on_scan(const lcm::ReceiveBuffer* b, const std::string&, Bus* self) {
    laser_scan_t scan;
    if (decode_message(b->data, b->data_size, &scan) == DecodeStatus::kOk) {
      self->scans.push_back(scan);
      self->scan_times.push_back(Clock::now());
    }
  }
  static void on_status(const lcm::ReceiveBuffer* b, const std::string&, Bus* self) {
    process_status_t status;
    if (decode_message(b->data, b->data_size, &status) == DecodeStatus::kOk && status.process == "slamer-urg") {
      self->statuses.push_back(status);
      self->status_times.push_back(Clock::now());
    }
  }
  bool pump_until(const std::function<bool()>& done, double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done()) {
      if (Clock::now() > deadline) {
        return false;
      }
      lcm.handleTimeout(10);
    }
    return true;
  }
  void pump_for(double seconds) {
    pump_until([] { return false; }, seconds);
  }
  // The index of the first scan after a gap longer than `gap`, 0 if none yet.
  std::size_t first_after_gap(std::chrono::milliseconds gap) const {
    for (std::size_t i = 1; i < scan_times.size(); ++i) {
      if (scan_times[i] - scan_times[i - 1] > gap) {
        return i;
      }
    }
    return 0;
  }
  lcm::LCM lcm;
  std::vector<laser_scan_t> scans;
  std::vector<Clock::time_point> scan_times;
  std::vector<process_status_t> statuses;
  std::vector<Clock::time_point> status_times;
};

using test::free_port;
using test::temp_path;

std::unique_ptr<test::ChildProcess> start_sim(std::vector<std::string> args, int* port) {
  return test::start_urg_sim(std::move(args), port);
}

std::unique_ptr<test::ChildProcess> start_driver(const std::string& url, int port,
                                                 std::vector<std::string> extra = {}) {
  return test::start_urg(url, port, extra);
}

TEST(UrgProcess, PublishesScansWithPpGeometryAndTheSceneRanges) {
  const std::string url = test::unique_lcm_url(1);
  Bus bus(url);
  int port = 0;
  auto sim = start_sim({"--model", "URM-40LC", "--jitter-ms", "5", "--segment-max", "100"}, &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return bus.scans.size() >= 60 && !bus.statuses.empty(); }, 6.0))
      << driver->stderr_text();
  urg::SimModel model;
  urg::sim_model("URM-40LC", &model);
  const urg::SimSensor truth(model, {});
  const laser_scan_t& s = bus.scans.back();
  ASSERT_EQ(s.nranges, 1081);
  EXPECT_EQ(s.nintensities, 0);
  EXPECT_NEAR(s.angle_min, -3 * std::numbers::pi / 4, 1e-9);
  EXPECT_NEAR(s.angle_increment, 2 * std::numbers::pi / 1440, 1e-12);
  EXPECT_FLOAT_EQ(s.range_min, 0.06f);
  EXPECT_FLOAT_EQ(s.range_max, 30.0f);
  EXPECT_FLOAT_EQ(s.scan_period, 0.025f);
  for (int i = 0; i < 1081; i += 7) {
    const float r = s.ranges[static_cast<std::size_t>(i)];
    if (urg::SimSensor::no_echo_step(i)) {
      EXPECT_EQ(r, INFINITY);
    } else {
      EXPECT_NEAR(r, std::floor(truth.range_mm(i)) / 1000.0, 1e-6) << i;
    }
  }
  for (std::size_t i = 1; i < bus.scans.size(); ++i) {
    EXPECT_EQ(bus.scans[i].seq, bus.scans[i - 1].seq + 1);  // each scan exactly once
    EXPECT_NEAR(static_cast<double>(bus.scans[i].sensor_utime - bus.scans[i - 1].sensor_utime), 25000.0, 1000.0);
    EXPECT_NEAR(static_cast<double>(bus.scans[i].utime - bus.scans[i - 1].utime), 25000.0, 1000.0);
  }
  EXPECT_EQ(s.sensor_utime % 1000, 0);
  bus.pump_until([&] { return bus.statuses.back().state == process_status_t::OK; }, 3.0);
  EXPECT_EQ(bus.statuses.back().state, process_status_t::OK) << bus.statuses.back().message;
  EXPECT_NE(bus.statuses.back().message.find("URM-40LC-EW"), std::string::npos) << bus.statuses.back().message;
}

TEST(UrgProcess, DamagedRepliesAreCountedNotPublished) {
  const std::string url = test::unique_lcm_url(2);
  Bus bus(url);
  int port = 0;
  const test::TempDir dir("urg_truth");  // removed with the file after the simulator stops
  const std::string truth = dir.file("truth.txt");
  auto sim = start_sim({"--model", "UTM-30LX", "--bad-checksum-rate", "0.05", "--truncate-rate", "0.05",
                        "--garbage-rate", "0.02", "--segment-max", "13", "--truth", truth},
                       &port);
  auto driver = start_driver(url, port, {});
  bus.pump_until([&] { return bus.scans.size() >= 100; }, 8.0);
  ASSERT_GE(bus.scans.size(), 100u) << driver->stderr_text();
  for (const auto& s : bus.scans) {
    ASSERT_EQ(s.nranges, 1081);
  }
  bus.pump_until(
      [&] {
        return !bus.statuses.empty() && bus.statuses.back().message.find("checksum 0 ") == std::string::npos &&
               bus.statuses.back().message.find("truncated 0 ") == std::string::npos;
      },
      4.0);
  ASSERT_FALSE(bus.statuses.empty());
  EXPECT_GT(bus.statuses.back().drops, 0) << bus.statuses.back().message;
  EXPECT_EQ(bus.statuses.back().message.find("checksum 0 "), std::string::npos) << bus.statuses.back().message;
  EXPECT_EQ(bus.statuses.back().message.find("truncated 0 "), std::string::npos) << bus.statuses.back().message;
  // At least 90 % of the intact scans are published.
  const std::string text = test::read_file(truth);
  const auto sent = std::count(text.begin(), text.end(), '\n') - 1;
  EXPECT_GE(static_cast<double>(bus.scans.size()), 0.9 * 0.88 * static_cast<double>(sent) - 45) << sent;
}

// Scans arrive again within 2 s of the sensor accepting connections.
void expect_recovers(Bus& bus, double sensor_back_s, const char* what) {
  const std::size_t before = bus.scans.size();
  const auto back = Clock::now() + std::chrono::duration<double>(sensor_back_s);
  bus.pump_until([&] { return bus.scans.size() > before + 5 && Clock::now() > back; }, sensor_back_s + 4.0);
  ASSERT_GT(bus.scans.size(), before + 5) << what;
  auto first_new = bus.scan_times.begin() + static_cast<std::ptrdiff_t>(before);
  const double after_back = std::chrono::duration<double>(*first_new - back).count();
  EXPECT_LT(after_back, 2.0) << what;
}

TEST(UrgProcess, SensorRefusingThenAppearing) {
  const std::string url = test::unique_lcm_url(3);
  Bus bus(url);
  int port = free_port();
  auto driver = start_driver(url, port);
  bus.pump_until([&] { return bus.statuses.size() >= 2; }, 4.0);
  ASSERT_FALSE(bus.statuses.empty());
  EXPECT_EQ(bus.statuses.back().state, process_status_t::DEGRADED);
  EXPECT_NE(bus.statuses.back().message.find("refused"), std::string::npos) << bus.statuses.back().message;
  auto sim = start_sim({"--model", "UTM-30LX"}, &port);
  expect_recovers(bus, 0.0, "refused");
  EXPECT_TRUE(driver->running());
}

TEST(UrgProcess, SensorResetAndDownThenBack) {
  const std::string url = test::unique_lcm_url(4);
  Bus bus(url);
  int port = 0;
  // The sensor closes the first connection 1.5 s after it opened and refuses connections for 1.5 s.
  auto sim = start_sim({"--model", "UST-10LX", "--drop-after", "1.5", "--down", "1.5"}, &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return !bus.scans.empty(); }, 4.0)) << driver->stderr_text();
  // The outage is found in the scans themselves: the driver's handshake takes a varying time on a
  // loaded machine, so the first scan says little about when the sensor dropped the connection.
  const auto gap_at = [&] { return bus.first_after_gap(std::chrono::milliseconds(500)); };
  ASSERT_TRUE(bus.pump_until([&] { return gap_at() > 0 && bus.scans.size() > gap_at() + 5; }, 9.0))
      << "scans " << bus.scans.size() << "\n"
      << driver->stderr_text();
  const std::size_t gap = gap_at();
  const auto gap_start = bus.scan_times[gap - 1], gap_end = bus.scan_times[gap];
  const double gap_s = std::chrono::duration<double>(gap_end - gap_start).count();
  // The sensor was really unreachable, and scans came back within 2 s of it accepting connections
  // again (1.5 s after its last scan).
  EXPECT_GT(gap_s, 1.4);
  EXPECT_LT(gap_s - 1.5, 2.0);
  // While scans were missing the driver said so: some PROCESS_STATUS in the gap is DEGRADED.
  bool degraded_in_gap = false;
  std::string messages;
  for (std::size_t i = 0; i < bus.statuses.size(); ++i) {
    if (bus.status_times[i] > gap_start && bus.status_times[i] < gap_end) {
      degraded_in_gap = degraded_in_gap || bus.statuses[i].state == process_status_t::DEGRADED;
      messages += bus.statuses[i].message + "\n";
    }
  }
  EXPECT_TRUE(degraded_in_gap) << "gap " << gap_s << " s; statuses in it:\n" << messages;
}

TEST(UrgProcess, SilentConnectionIsDroppedAndScansResume) {
  const std::string url = test::unique_lcm_url(5);
  Bus bus(url);
  int port = 0;
  auto sim = start_sim({"--model", "URM-40LC", "--silent-after", "1.0"}, &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return bus.scans.size() > 10; }, 4.0)) << driver->stderr_text();
  // A gap of more than 3 periods (the silent connection), then scans again from a new connection.
  const auto gap_at = [&] { return bus.first_after_gap(std::chrono::milliseconds(75)); };
  ASSERT_TRUE(bus.pump_until([&] { return gap_at() > 0 && bus.scans.size() > gap_at() + 5; }, 6.0))
      << "scans " << bus.scans.size() << "\n"
      << driver->stderr_text();
  // Silence is noticed within a few periods and the reconnection is quick: well under a second.
  const double gap_s = std::chrono::duration<double>(bus.scan_times[gap_at()] - bus.scan_times[gap_at() - 1]).count();
  EXPECT_LT(gap_s, 1.0);
}

TEST(UrgProcess, Scip11SensorIsSwitchedTo20) {
  const std::string url = test::unique_lcm_url(6);
  Bus bus(url);
  int port = 0;
  auto sim = start_sim({"--model", "URG-04LX"}, &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return bus.scans.size() >= 5; }, 5.0)) << driver->stderr_text();
  EXPECT_EQ(bus.scans.back().nranges, 682);  // AMIN 44 .. AMAX 725
  EXPECT_NEAR(bus.scans.back().angle_min, (44 - 384) * 2 * std::numbers::pi / 1024, 1e-9);
  EXPECT_FLOAT_EQ(bus.scans.back().range_max, 5.6f);
}

TEST(UrgProcess, GeometryChangeAfterRebootUsesTheNewPp) {
  const std::string url = test::unique_lcm_url(7);
  Bus bus(url);
  int port = 0;
  auto sim = start_sim(
      {"--model", "URG-04LX", "--error-after", "15", "--error-survives-reset", "--model-after-reboot", "UTM-30LX"},
      &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return !bus.scans.empty() && bus.scans.back().nranges == 1081; }, 10.0))
      << driver->stderr_text();
  EXPECT_EQ(bus.scans.front().nranges, 682);
  // The status names the new model and counts the reboot. The emulated laser fails again
  // 15 scans after each power-up, so on a slow machine the first status may count more.
  const auto reboots = [](const std::string& message) {
    const std::size_t at = message.find("reboots ");
    return at == std::string::npos ? 0 : std::stoi(message.substr(at + 8));
  };
  EXPECT_TRUE(bus.pump_until(
      [&] {
        return !bus.statuses.empty() && reboots(bus.statuses.back().message) >= 1 &&
               bus.statuses.back().message.find("streaming UTM-30LX") != std::string::npos;
      },
      3.0))
      << (bus.statuses.empty() ? "no status" : bus.statuses.back().message);
}

TEST(UrgProcess, SerialPathOverAPty) {
  const std::string url = test::unique_lcm_url(8);
  Bus bus(url);
  const std::string link = temp_path("urg_pty");
  std::filesystem::remove(link);
  test::ChildProcess sim(test::binary_path("slamer-urg-sim"), {"--model", "URG-04LX", "--pty", "--pty-link", link});
  for (int i = 0; i < 200 && !std::filesystem::is_symlink(link); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  auto driver = start_driver(url, 1, {"--device", link});
  ASSERT_TRUE(bus.pump_until([&] { return bus.scans.size() >= 5; }, 6.0)) << driver->stderr_text();
  EXPECT_EQ(bus.scans.back().nranges, 682);
  std::filesystem::remove(link);
}

// --source-log: a log's scans at their own pace, each once, with their ranges; the emulator exits after the last.
TEST(UrgProcess, ScansFromALogAtTheirOwnPace) {
  const std::string log_path = temp_path("urg_source") + ".lcm";
  {
    lcm::LogFile log(log_path, "w");
    for (int k = 0; k < 60; ++k) {
      laser_scan_t scan{};
      scan.utime = 1'700'000'000'000'000 + k * 25000;
      scan.frame = "laser";
      scan.angle_min = -0.75 * std::numbers::pi;
      scan.angle_increment = 2 * std::numbers::pi / 1440;
      scan.range_min = 0.06f;
      scan.range_max = 30.0f;
      scan.scan_period = 0.025f;
      scan.nranges = 1081;
      scan.ranges.assign(1081, 1.0f + 0.01f * static_cast<float>(k));
      scan.ranges[5] = INFINITY;
      scan.nintensities = 0;
      std::vector<uint8_t> bytes(static_cast<std::size_t>(scan.getEncodedSize()));
      scan.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
      lcm::LogEvent event{k, scan.utime, "SIM_SCANS", static_cast<int32_t>(bytes.size()), bytes.data()};
      ASSERT_EQ(log.writeEvent(&event), 0);
    }
  }
  const std::string url = test::unique_lcm_url(9);
  Bus bus(url);
  int port = 0;
  auto sim = start_sim({"--source-log", log_path, "--source-channel", "SIM_SCANS"}, &port);
  auto driver = start_driver(url, port);
  ASSERT_TRUE(bus.pump_until([&] { return !sim->running(); }, 15.0)) << sim->stderr_text();
  EXPECT_NE(sim->stdout_text().find("the scan source has ended"), std::string::npos) << sim->stdout_text();
  bus.pump_for(0.2);
  ASSERT_EQ(bus.scans.size(), 60u) << driver->stderr_text();
  for (std::size_t k = 0; k < bus.scans.size(); ++k) {
    const laser_scan_t& s = bus.scans[k];
    EXPECT_FLOAT_EQ(s.ranges[0], std::round((1.0f + 0.01f * static_cast<float>(k)) * 1000.0f) / 1000.0f) << k;
    EXPECT_EQ(s.ranges[5], INFINITY);
    if (k > 0) {
      EXPECT_NEAR(static_cast<double>(s.utime - bus.scans[k - 1].utime), 25000.0, 1000.0) << k;
    }
  }
  std::filesystem::remove(log_path);
}

}  // namespace
}  // namespace slamer

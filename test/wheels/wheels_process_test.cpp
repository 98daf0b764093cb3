// End-to-end: the real slamer-wheels against slamer-tfrog-sim (a pty) and
// slamer-can-source (a SEQPACKET socket), observed over LCM on loopback.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>

#include "common/geometry/se2.hpp"
#include "common/process/decode.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/process_status_t.hpp"
#include "slamer/velocity_command_t.hpp"
#include "slamer/wheel_encoders_t.hpp"
#include "test/support/child_process.hpp"
#include "test/support/driver_processes.hpp"

namespace slamer {
namespace {

using test::binary_path;
using test::ChildProcess;

int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

class Bus {
 public:
  explicit Bus(const std::string& url) : lcm_(url) {
    subscribe<odometry_t>("ODOMETRY", &odometry);
    subscribe<wheel_encoders_t>("WHEEL_ENCODERS", &encoders);
    subscribe<process_status_t>("PROCESS_STATUS", &status);
  }
  bool pump_until(const std::function<bool()>& done, double timeout_s, const std::function<void()>& every_50ms = {}) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    auto next = std::chrono::steady_clock::now();
    while (!done()) {
      if (std::chrono::steady_clock::now() >= deadline) {
        return false;
      }
      if (every_50ms && std::chrono::steady_clock::now() >= next) {
        every_50ms();
        next += std::chrono::milliseconds(50);
      }
      // Drain everything queued: 200 Hz ODOMETRY + WHEEL_ENCODERS must not pile up behind us.
      if (lcm_.handleTimeout(5) > 0) {
        while (lcm_.handleTimeout(0) > 0) {
        }
      }
    }
    return true;
  }
  void pump_for(double seconds, const std::function<void()>& every_50ms = {}) {
    pump_until([] { return false; }, seconds, every_50ms);
  }
  // Pumps until ODOMETRY and WHEEL_ENCODERS have caught up with `utime` (a loaded machine lags).
  bool catch_up(int64_t utime, double timeout_s) {
    return pump_until(
        [&] {
          return !odometry.empty() && odometry.back().utime >= utime && !encoders.empty() &&
                 encoders.back().utime >= utime;
        },
        timeout_s);
  }
  void command(double v, double omega) {
    velocity_command_t msg{};
    msg.utime = wall_utime();
    msg.v = v;
    msg.omega = omega;
    lcm_.publish("CMD_VEL", &msg);
    last_command = msg.utime;
  }
  std::vector<odometry_t> odometry;
  std::vector<wheel_encoders_t> encoders;
  std::vector<process_status_t> status;
  int64_t last_command = 0;

 private:
  template <class Msg>
  void subscribe(const std::string& channel, std::vector<Msg>* store) {
    handlers_.push_back(
        std::make_unique<std::function<void(const lcm::ReceiveBuffer*)>>([store](const lcm::ReceiveBuffer* buffer) {
          Msg msg;
          if (decode_message(buffer->data, buffer->data_size, &msg) == DecodeStatus::kOk) {
            store->push_back(msg);
          }
        }));
    lcm_.subscribeFunction(
        channel,
        +[](const lcm::ReceiveBuffer* b, const std::string&, std::function<void(const lcm::ReceiveBuffer*)>* f) {
          (*f)(b);
        },
        handlers_.back().get());
  }
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<std::function<void(const lcm::ReceiveBuffer*)>>> handlers_;
};

// Lines "<utime> <word> ..." of an emulator's stdout.
struct SimLine {
  int64_t utime = 0;
  std::string word;
  std::vector<double> values;
};
std::vector<SimLine> sim_lines(const std::string& text) {
  std::vector<SimLine> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    SimLine l;
    std::string token;
    if (!(fields >> l.utime >> l.word)) {
      continue;
    }
    while (fields >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end != token.c_str()) {
        l.values.push_back(v);
      }
    }
    lines.push_back(l);
  }
  return lines;
}
std::optional<SimLine> find_line(const std::string& text, const std::string& word) {
  for (const auto& l : sim_lines(text)) {
    if (l.word == word) {
      return l;
    }
  }
  return std::nullopt;
}

struct Rig {
  explicit Rig(int salt, const std::vector<std::string>& sim_args)
      : url(test::unique_lcm_url(salt)),
        link("/tmp/slamer_wheels_test_" + std::to_string(getpid()) + "_" + std::to_string(salt)),
        bus(url) {
    sim = test::start_tfrog_sim(link, sim_args);
    wheels = test::start_wheels(url, link);
  }
  std::string url;
  std::string link;
  Bus bus;
  std::unique_ptr<ChildProcess> sim;
  std::unique_ptr<ChildProcess> wheels;
};

// 50.0 m: straight, left and right quarter turns, an 8 m reverse, a spin, a long arc.
const char* kPath50 = "8,0,1.5;4,4,0.39269908;8,0,1.0;4,-2,0.78539816;-8,0,1.0;0,3,0.52359878;8,1,1.5;6,0,0.88144";

TEST(WheelsProcess, FiftyMetrePathWithTurnsAndReverse) {
  Rig rig(11, {"--path", kPath50, "--path-delay", "0.3"});
  ASSERT_TRUE(rig.bus.pump_until([&] { return rig.sim->stdout_text().find("path-done") != std::string::npos; }, 20.0))
      << rig.wheels->stderr_text();
  const auto done = find_line(rig.sim->stdout_text(), "path-done");
  ASSERT_TRUE(done && done->values.size() == 5);
  ASSERT_TRUE(rig.bus.catch_up(done->utime + 100'000, 5.0));
  const double distance = done->values[3];
  EXPECT_NEAR(distance, 50.0, 0.01);
  ASSERT_FALSE(rig.bus.odometry.empty());
  const odometry_t last = rig.bus.odometry.back();
  const double position_error = std::hypot(last.x - done->values[0], last.y - done->values[1]);
  EXPECT_LT(position_error, 0.001 * distance)
      << "board sent " << done->values[4] << " frames; "
      << (rig.bus.status.empty() ? "" : rig.bus.status.back().message) << "\n"
      << rig.wheels->stderr_text() << last.x << " " << last.y << " vs " << done->values[0] << " " << done->values[1];
  EXPECT_LT(std::fabs(angle_diff(last.theta, done->values[2])), 0.5 * M_PI / 180.0);
  // One message per frame: seq and utime rise (UDP multicast may drop a few on a loaded machine).
  for (std::size_t i = 1; i < rig.bus.odometry.size(); ++i) {
    ASSERT_GT(rig.bus.odometry[i].seq, rig.bus.odometry[i - 1].seq);
    ASSERT_GT(rig.bus.odometry[i].utime, rig.bus.odometry[i - 1].utime);
  }
  EXPECT_GT(rig.bus.odometry.size(), static_cast<std::size_t>(0.9 * static_cast<double>(last.seq)));
  ASSERT_FALSE(rig.bus.encoders.empty());
  const auto& enc = rig.bus.encoders.back();
  ASSERT_EQ(enc.nwheels, 2);
  EXPECT_EQ(enc.source, "tfrog");
  // Forward-positive: net forward travel of each wheel in counts (~1.5 million counts, many int16 wraps).
  EXPECT_GT(enc.ticks[0], 1000000);
  EXPECT_GT(enc.ticks[1], 1000000);
  // Nothing was damaged on the pty. (Lost frames are not asserted: a starved
  // emulator skips time, which the driver rightly counts as lost frames.)
  rig.bus.pump_until([&] { return !rig.bus.status.empty(); }, 2.0);
  ASSERT_FALSE(rig.bus.status.empty());
  const std::string& message = rig.bus.status.back().message;
  EXPECT_NE(message.find("damaged 0, wrong length 0"), std::string::npos) << message;
  EXPECT_TRUE(rig.wheels->running());
}

TEST(WheelsProcess, DamagedDroppedAndShortFramesAreCountedNotFatal) {
  Rig rig(12, {"--path", "6,0.5,1.0", "--corrupt-every", "7", "--drop-every", "13", "--wrong-length-every", "11"});
  ASSERT_TRUE(rig.bus.pump_until([&] { return rig.sim->stdout_text().find("path-done") != std::string::npos; }, 10.0));
  const auto done = find_line(rig.sim->stdout_text(), "path-done");
  ASSERT_TRUE(done);
  ASSERT_TRUE(rig.bus.catch_up(done->utime + 100'000, 5.0));
  rig.bus.pump_for(1.2);  // a status period
  ASSERT_FALSE(rig.bus.odometry.empty());
  const odometry_t last = rig.bus.odometry.back();
  // Counts are absolute: a lost frame loses no travel.
  EXPECT_LT(std::hypot(last.x - done->values[0], last.y - done->values[1]), 0.001 * done->values[3]);
  bool counted = false;
  for (const auto& s : rig.bus.status) {
    if (s.process == "slamer-wheels" && s.drops > 0 && s.message.find("damaged 0") == std::string::npos &&
        s.message.find("lost 0,") == std::string::npos) {
      counted = true;
    }
  }
  EXPECT_TRUE(counted) << (rig.bus.status.empty() ? "" : rig.bus.status.back().message);
  EXPECT_TRUE(rig.wheels->running());
}

TEST(WheelsProcess, UnplugReplugReconnectsAndOdometryContinues) {
  Rig rig(13, {"--path", "2,0,1", "--path-delay", "0.2", "--unplug-at", "2.5", "--replug-after", "0.5"});
  auto replug_utime = [&]() -> int64_t {
    bool unplugged = false;
    for (const auto& l : sim_lines(rig.sim->stdout_text())) {
      unplugged = unplugged || l.word == "unplugged";
      if (unplugged && l.word == "plugged") {
        return l.utime;
      }
    }
    return 0;
  };
  ASSERT_TRUE(rig.bus.pump_until([&] { return replug_utime() > 0; }, 10.0));
  const int64_t replug = replug_utime();
  const int64_t unplug = find_line(rig.sim->stdout_text(), "unplugged")->utime;
  // Odometry resumes within 2 s of the re-plug.
  auto resumed = [&] { return !rig.bus.odometry.empty() && rig.bus.odometry.back().utime > replug; };
  ASSERT_TRUE(rig.bus.pump_until(resumed, 3.0)) << rig.wheels->stderr_text();
  std::optional<odometry_t> before;
  std::optional<odometry_t> after;
  std::optional<wheel_encoders_t> enc_before;
  for (const auto& o : rig.bus.odometry) {
    before = o.utime < unplug ? std::optional<odometry_t>(o) : before;
    after = (!after && o.utime > replug) ? std::optional<odometry_t>(o) : after;
  }
  for (const auto& e : rig.bus.encoders) {
    enc_before = e.utime < unplug ? std::optional<wheel_encoders_t>(e) : enc_before;
  }
  ASSERT_TRUE(before && after && enc_before);
  EXPECT_LT(after->utime - replug, 2'000'000);
  ASSERT_TRUE(rig.bus.catch_up(after->utime + 200'000, 5.0));
  // No jump although the re-plugged board restarted its counters at 0.
  EXPECT_NEAR(rig.bus.odometry.back().x, before->x, 1e-9);
  EXPECT_NEAR(rig.bus.odometry.back().theta, before->theta, 1e-9);
  EXPECT_EQ(rig.bus.encoders.back().ticks, enc_before->ticks);
  EXPECT_NEAR(before->x, 2.0, 0.002);
  // PROCESS_STATUS (1 Hz) reports the reconnect once the board runs again (a status
  // during the new handshake says "connecting", DEGRADED: on a loaded machine one does).
  auto reported = [&] {
    return !rig.bus.status.empty() && rig.bus.status.back().message.find("reconnects 1") != std::string::npos &&
           rig.bus.status.back().message.find(" running;") != std::string::npos;
  };
  EXPECT_TRUE(rig.bus.pump_until(reported, 5.0)) << rig.bus.status.back().message;
  EXPECT_EQ(rig.bus.status.back().state, process_status_t::OK) << rig.bus.status.back().message;
  EXPECT_TRUE(rig.wheels->running());
}

TEST(WheelsProcess, CommandTimeoutStopsTheWheelsAndTheyStayStopped) {
  Rig rig(14, {});
  ASSERT_TRUE(rig.bus.pump_until([&] { return rig.bus.odometry.size() > 20; }, 5.0)) << rig.wheels->stderr_text();
  rig.bus.pump_for(1.0, [&] { rig.bus.command(0.3, 0.2); });
  const int64_t last_command = rig.bus.last_command;
  rig.bus.pump_for(1.5);
  // The final stop: the first all-zero line after the last line that drove.
  bool drove = false;
  int64_t stopped = 0;
  int64_t last_drive = 0;
  for (const auto& l : sim_lines(rig.sim->stdout_text())) {
    if (l.word != "servo" || l.values.size() != 4) {
      continue;
    }
    if (l.values[0] == 3 && (l.values[2] != 0 || l.values[3] != 0)) {
      drove = true;
      stopped = 0;
      last_drive = l.utime;
    } else if (drove && stopped == 0 && l.values[2] == 0 && l.values[3] == 0) {
      stopped = l.utime;
    }
  }
  EXPECT_TRUE(drove);
  ASSERT_GT(stopped, 0);
  EXPECT_LT(stopped - last_command, 300'000);
  EXPECT_LT(last_drive - last_command, 300'000);  // and never drove again without a command
  EXPECT_TRUE(rig.wheels->running());
  // A clean exit leaves both servos at STOP.
  rig.wheels->signal(SIGINT);
  EXPECT_EQ(rig.wheels->wait(5.0), std::optional<int>(0));
  rig.bus.pump_for(0.1);
  std::optional<SimLine> last_state;
  for (const auto& l : sim_lines(rig.sim->stdout_text())) {
    last_state = l.word == "servo" ? std::optional<SimLine>(l) : last_state;
  }
  ASSERT_TRUE(last_state);
  EXPECT_EQ(last_state->values, (std::vector<double>{0, 0, 0, 0}));
}

TEST(WheelsProcess, KilledDriverIsStoppedByTheBoardWatchdog) {
  Rig rig(15, {});
  ASSERT_TRUE(rig.bus.pump_until([&] { return rig.bus.odometry.size() > 20; }, 5.0));
  rig.bus.pump_for(0.5, [&] { rig.bus.command(0.4, 0.0); });
  rig.wheels->signal(SIGKILL);
  const int64_t killed = wall_utime();
  rig.wheels->wait(2.0);
  rig.bus.pump_for(0.8);
  const auto watchdog = find_line(rig.sim->stdout_text(), "watchdog");
  ASSERT_TRUE(watchdog) << rig.sim->stdout_text();
  EXPECT_LT(watchdog->utime - killed, 400'000);  // watchdog 300 ms
  std::optional<SimLine> last_state;
  for (const auto& l : sim_lines(rig.sim->stdout_text())) {
    last_state = l.word == "servo" ? std::optional<SimLine>(l) : last_state;
  }
  ASSERT_TRUE(last_state);
  EXPECT_EQ(last_state->values, (std::vector<double>{0, 0, 0, 0}));  // servo STOP, wheels stopped
}

TEST(WheelsProcess, CanEncodersWithBusOffGarbageAndShortFrames) {
  const std::string url = test::unique_lcm_url(16);
  const std::string socket = "/tmp/slamer_can_test_" + std::to_string(getpid());
  Bus bus(url);
  ChildProcess source(binary_path("slamer-can-source"),
                      {"--listen", socket, "--robot", std::string(SLAMER_SOURCE_DIR "/config/robots/icart-mini.param"),
                       "--path", "1,0.5,2", "--bus-off-at", "2.5", "--bus-off-for", "1.5", "--garbage-every", "50",
                       "--wrong-length-every", "70", "--duration", "8"});
  ChildProcess wheels(binary_path("slamer-wheels"), {"--config", std::string(SLAMER_SOURCE_DIR "/config/wheels.yaml"),
                                                     "--can", "unix:" + socket, "--lcm-url", url});
  ASSERT_TRUE(bus.pump_until([&] { return source.stdout_text().find("restarted") != std::string::npos; }, 10.0))
      << wheels.stderr_text();
  // The bus recovered: a later PROCESS_STATUS (1 Hz) no longer says BUS-OFF.
  const std::size_t at_restart = bus.status.size();
  bus.pump_until([&] { return bus.status.size() >= at_restart + 2; }, 3.0);
  const auto done = find_line(source.stdout_text(), "path-done");
  ASSERT_TRUE(done);
  ASSERT_FALSE(bus.odometry.empty());
  ASSERT_TRUE(bus.catch_up(done->utime + 100'000, 5.0));
  const odometry_t last = bus.odometry.back();
  EXPECT_LT(std::hypot(last.x - done->values[0], last.y - done->values[1]), 0.001 * done->values[3] + 0.0005);
  EXPECT_LT(std::fabs(angle_diff(last.theta, done->values[2])), 0.5 * M_PI / 180.0);
  EXPECT_EQ(bus.encoders.back().source, "can");
  bool saw_bus_off = false;
  for (const auto& s : bus.status) {
    if (s.process == "slamer-wheels" && s.message.find("BUS-OFF") != std::string::npos) {
      saw_bus_off = true;
      EXPECT_EQ(s.state, process_status_t::DEGRADED);
    }
  }
  EXPECT_TRUE(saw_bus_off);
  ASSERT_FALSE(bus.status.empty());
  EXPECT_EQ(bus.status.back().message.find("BUS-OFF"), std::string::npos)
      << bus.status.back().message << "\n"
      << wheels.stderr_text() << source.stdout_text();
  EXPECT_GT(bus.status.back().drops, 0);  // the garbage datagrams
  EXPECT_TRUE(wheels.running());
}

}  // namespace
}  // namespace slamer

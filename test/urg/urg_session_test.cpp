// The session state machine against the emulator's sensor, in one process on a
// simulated clock: start-up, SCIP 1.1, time-adjust, draining, faults, reboot,
// geometry change, timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "drivers/urg/urg_session.hpp"
#include "tools/urg_sim/sim_sensor.hpp"

namespace slamer::urg {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

struct Harness {
  SimSensor sensor;
  UrgSession session;
  int64_t now = kT0;
  bool connected = false;
  int64_t reconnect_at = 0;
  int64_t sensor_back_at = 0;
  std::vector<LaserScan> scans;
  std::vector<SimTruth> truth;
  int disconnects = 0;

  Harness(const std::string& model, SimKnobs knobs, UrgSessionOptions options = {})
      : sensor(make_model(model), knobs), session(options) {
    sensor.power_on(now);
  }
  static SimModel make_model(const std::string& name) {
    SimModel m;
    EXPECT_TRUE(sim_model(name, &m)) << name;
    return m;
  }
  void connect() {
    connected = true;
    session.connected(now);
  }
  void run(double seconds) {
    const int64_t end = now + static_cast<int64_t>(seconds * 1e6);
    while (now < end) {
      now += 250;
      if (sensor_back_at > 0 && now >= sensor_back_at) {
        sensor.power_on(now);
        sensor_back_at = 0;
      }
      if (!connected) {
        if (sensor_back_at == 0 && now >= reconnect_at) {
          connect();
        }
        continue;
      }
      const std::string in = sensor.poll(now);
      if (!in.empty()) {
        session.received(in, now);
      }
      session.tick(now);
      const std::string out = session.take_output();
      if (!out.empty()) {
        sensor.receive(out, now);
      }
      for (auto& s : session.take_scans()) {
        scans.push_back(std::move(s));
      }
      for (auto& t : sensor.take_truth()) {
        truth.push_back(t);
      }
      if (sensor.reboot_requested()) {
        sensor_back_at = now + 300000;  // the sensor is gone for 0.3 s
      }
      if (session.should_disconnect() || sensor_back_at > 0) {
        session.disconnected();
        connected = false;
        ++disconnects;
        reconnect_at = now + 100000;
      }
    }
  }
};

TEST(UrgSession, StartsUpAndStreamsWholeRangeOfUrm40lc) {
  Harness h("URM-40LC", {});
  h.connect();
  h.run(1.0);
  ASSERT_EQ(h.session.state(), UrgSession::State::kStreaming) << h.session.last_error();
  ASSERT_GT(h.scans.size(), 30u);
  EXPECT_EQ(h.session.model(), "URM-40LC-EW");
  EXPECT_EQ(h.session.serial(), "H0000001");
  const LaserScan& s = h.scans.back();
  ASSERT_EQ(s.ranges.size(), 1081u);
  EXPECT_TRUE(s.intensities.empty());
  EXPECT_NEAR(s.angle_min, -3 * std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(s.angle_increment, 2 * std::numbers::pi / 1440, 1e-15);
  EXPECT_FLOAT_EQ(s.range_min, 0.06f);
  EXPECT_FLOAT_EQ(s.range_max, 30.0f);
  EXPECT_FLOAT_EQ(s.scan_period, 0.025f);
  EXPECT_FLOAT_EQ(s.time_increment, 0.025f / 1440);
  for (int i = 0; i < 1081; ++i) {
    if (SimSensor::no_echo_step(i)) {
      EXPECT_EQ(s.ranges[static_cast<std::size_t>(i)], INFINITY) << i;
    } else {
      EXPECT_NEAR(s.ranges[static_cast<std::size_t>(i)], std::floor(h.sensor.range_mm(i)) / 1000.0, 1e-6) << i;
    }
  }
  EXPECT_EQ(h.scans[1].seq, h.scans[0].seq + 1);
  EXPECT_EQ(h.session.counters().checksum + h.session.counters().truncated + h.session.counters().length, 0);
  EXPECT_TRUE(h.session.clock().synced());
}

TEST(UrgSession, MeGivesIntensitiesAndAStepSubsetWithCluster) {
  UrgSessionOptions options;
  options.intensities = true;
  options.first_step = 100;
  options.last_step = 900;
  options.cluster = 3;
  Harness h("UTM-30LX", {}, options);
  h.connect();
  h.run(0.8);
  ASSERT_FALSE(h.scans.empty()) << h.session.last_error();
  const LaserScan& s = h.scans.back();
  ASSERT_EQ(s.ranges.size(), 267u);  // ceil(801 / 3)
  ASSERT_EQ(s.intensities.size(), 267u);
  EXPECT_FLOAT_EQ(s.intensities[1], static_cast<float>(1000 + (103 * 37) % 3000));
  EXPECT_NEAR(s.angle_min, (100 - 540) * 2 * std::numbers::pi / 1440, 1e-12);
  EXPECT_NEAR(s.angle_increment, 3 * 2 * std::numbers::pi / 1440, 1e-12);
}

TEST(UrgSession, SwitchesScip11SensorTo20) {
  Harness h("URG-04LX", {});
  h.connect();
  h.run(1.5);
  ASSERT_FALSE(h.scans.empty()) << h.session.last_error();
  EXPECT_EQ(h.session.counters().scip1_switches, 1);
  EXPECT_EQ(h.scans.back().ranges.size(), 682u);
  EXPECT_FLOAT_EQ(h.scans.back().scan_period, 0.1f);
}

TEST(UrgSession, LeavesTimeAdjustModeAndDrainsAStreamAlreadyRunning) {
  {
    Harness h("UTM-30LX", {});
    h.sensor.receive("TM0\n", h.now);
    (void)h.sensor.poll(h.now + 1000);
    h.connect();
    h.run(0.8);
    EXPECT_FALSE(h.scans.empty()) << h.session.last_error();
  }
  {
    Harness h("UTM-30LX", {});
    h.sensor.receive("MD0000108001000\n", h.now);
    h.now += 200000;
    (void)h.sensor.poll(h.now - 3000);  // scans already in flight when the driver connects
    h.connect();
    h.run(0.8);
    EXPECT_FALSE(h.scans.empty()) << h.session.last_error();
  }
}

TEST(UrgSession, DamagedScansAreCountedNotPublished) {
  SimKnobs knobs;
  knobs.bad_checksum_rate = 0.03;
  knobs.truncate_rate = 0.03;
  knobs.garbage_rate = 0.02;
  knobs.seed = 7;
  Harness h("URM-40LC", knobs);
  h.connect();
  h.run(5.0);
  const auto& c = h.session.counters();
  EXPECT_GT(c.checksum, 0);
  EXPECT_GT(c.truncated, 0);
  const int64_t sent = h.sensor.scans_sent();
  EXPECT_GE(static_cast<double>(h.scans.size()), 0.9 * static_cast<double>(sent - 1));
  for (const LaserScan& s : h.scans) {
    ASSERT_EQ(s.ranges.size(), 1081u);
  }
  EXPECT_EQ(h.disconnects, 0);
}

TEST(UrgSession, MalfunctionResetsThenRebootsAndUsesTheNewGeometry) {
  SimKnobs knobs;
  knobs.error_status = "50";
  knobs.error_after = 20;
  knobs.error_survives_reset = true;
  knobs.model_after_reboot = "UTM-30LX";
  Harness h("URG-04LX", knobs);
  h.connect();
  h.run(8.0);
  const auto& c = h.session.counters();
  EXPECT_GE(c.resets, 1);
  EXPECT_GE(c.reboots, 1);
  EXPECT_GE(c.malfunctions, 2);
  ASSERT_FALSE(h.scans.empty());
  EXPECT_EQ(h.scans.front().ranges.size(), 682u);
  EXPECT_EQ(h.scans.back().ranges.size(), 1081u);  // the PP after the reboot
  EXPECT_NEAR(h.scans.back().angle_min, -3 * std::numbers::pi / 4, 1e-12);
}

TEST(UrgSession, SilenceForThreeScanPeriodsDisconnects) {
  Harness h("URM-40LC", {});
  h.connect();
  h.run(0.8);
  ASSERT_TRUE(h.session.streaming());
  // The sensor goes quiet without closing: stop polling it.
  UrgSession& s = h.session;
  s.tick(h.now + 60000);
  EXPECT_FALSE(s.should_disconnect());
  s.tick(h.now + 120000);
  EXPECT_TRUE(s.should_disconnect());
  EXPECT_EQ(s.counters().silences, 1);
}

TEST(UrgSession, NoReplyAtAllMeansProbeUnanswered) {
  UrgSession s({});
  s.connected(kT0);
  EXPECT_EQ(s.take_output(), "QT\n");
  for (int i = 1; i <= 4; ++i) {
    s.tick(kT0 + i * 1'100'000);
  }
  EXPECT_TRUE(s.should_disconnect());
  EXPECT_TRUE(s.probe_unanswered());
  EXPECT_EQ(s.counters().timeouts, 3);
}

TEST(UrgSession, FirstBeamTimeWithDelayAndDrift) {
  for (double drift : {100.0, -100.0}) {
    SimKnobs knobs;
    knobs.jitter_ms = 5.0;
    knobs.drift_ppm = drift;
    knobs.seed = 3;
    Harness h("UTM-30LX", knobs);
    h.connect();
    h.run(30.0);
    ASSERT_GT(h.scans.size(), 1000u);
    std::vector<double> errors;
    for (const LaserScan& s : h.scans) {
      // Match by device stamp.
      for (auto it = h.truth.rbegin(); it != h.truth.rend(); ++it) {
        if (static_cast<int64_t>(it->device_stamp_ms) == (s.sensor_utime / 1000) % (int64_t{1} << 24)) {
          errors.push_back(std::abs(static_cast<double>(s.utime - it->first_beam_host_us)));
          break;
        }
      }
    }
    ASSERT_GT(errors.size(), 1000u);
    std::sort(errors.begin(), errors.end());
    std::printf("drift %+.0f ppm: p50 %.0f us, p99 %.0f us over %zu scans\n", drift, errors[errors.size() / 2],
                errors[errors.size() * 99 / 100], errors.size());
    EXPECT_LT(errors[errors.size() * 99 / 100], 1000.0) << drift;
    EXPECT_LT(errors[errors.size() / 2], 300.0) << drift;
    EXPECT_EQ(h.sensor.scans_sent() - static_cast<int64_t>(h.scans.size()), 0);  // none lost to time sync
  }
}

}  // namespace
}  // namespace slamer::urg

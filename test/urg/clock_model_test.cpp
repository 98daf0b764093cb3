// The clock model on a synthetic sensor: 0-5 ms uniform reply delay, +-100 ppm
// drift, TM1 bursts, a constant-period scan stream; first-beam time errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "drivers/urg/clock_model.hpp"

namespace slamer::urg {
namespace {

TEST(StampUnwrapper, Wraps24Bit) {
  StampUnwrapper u;
  EXPECT_EQ(u.unwrap(16777200), 16777200);
  EXPECT_EQ(u.unwrap(16777215), 16777215);
  EXPECT_EQ(u.unwrap(9), 16777216 + 9);
  EXPECT_EQ(u.unwrap(25), 16777216 + 25);
  EXPECT_EQ(u.unwrap(20), 16777216 + 20);  // a small step back stays back
  u.reset();
  EXPECT_EQ(u.unwrap(5), 5);
}

struct SyntheticSensor {
  double drift;       // device rate - 1
  double device0_us;  // device clock at host 0
  int64_t host0_us = 1'700'000'000'000'000;
  double device_us(double host_rel_us) const { return device0_us + (1.0 + drift) * host_rel_us; }
  int64_t device_ms(double host_rel_us) const {
    return static_cast<int64_t>(std::floor(device_us(host_rel_us) / 1000));
  }
};

struct Errors {
  double p50 = 0, p99 = 0, max = 0;
};

Errors percentiles(std::vector<double> e) {
  std::sort(e.begin(), e.end());
  Errors out;
  out.p50 = e[e.size() / 2];
  out.p99 = e[e.size() * 99 / 100];
  out.max = e.back();
  return out;
}

// Runs `seconds` of 40 Hz scans after one TM1 burst; returns |utime - truth| [us].
std::vector<double> run(double drift_ppm, double seconds, unsigned seed, double tm_tick_ms = 0,
                        bool tm_while_streaming = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> delay(0.0, 5000.0);
  std::uniform_real_distribution<double> phase(0.0, 25000.0);
  SyntheticSensor sensor{drift_ppm * 1e-6, 123456789.0 + phase(rng)};
  ClockModel model;
  // TM1 burst: each request is read at once (or on the next tm_tick), each reply takes 0-5 ms.
  std::vector<SyncSample> samples;
  double t = 1000.0;
  auto tm1 = [&](double send) {
    double read = send + 50.0;
    if (tm_tick_ms > 0) {
      const double device = sensor.device_us(read) / 1000.0;
      read += (std::ceil(device / tm_tick_ms) * tm_tick_ms - device) * 1000.0;
    }
    const double arrive = read + delay(rng);
    return SyncSample{sensor.host0_us + static_cast<int64_t>(send), sensor.host0_us + static_cast<int64_t>(arrive),
                      sensor.device_ms(read)};
  };
  for (int i = 0; i < 40; ++i) {
    samples.push_back(tm1(t));
    t = static_cast<double>(samples.back().receive_us - sensor.host0_us) + 100.0;
  }
  EXPECT_TRUE(model.sync(samples));
  // Scans: first beam every 25 ms of host time from a random phase; the reply leaves 18.75 ms later.
  std::vector<double> errors;
  const double first = t + 20000.0 + phase(rng);
  const int n = static_cast<int>(seconds * 40);
  for (int k = 0; k < n; ++k) {
    const double beam = first + k * 25000.0;
    const double arrival = beam + 18750.0 + delay(rng);
    if (tm_while_streaming && k % 2 == 0) {
      model.add_sync_sample(tm1(beam + 4.0 * delay(rng)));  // a TM1 between scans, 20 Hz
    }
    const int64_t utime =
        model.scan_utime(sensor.device_ms(beam), 25000, sensor.host0_us + static_cast<int64_t>(arrival));
    errors.push_back(std::abs(static_cast<double>(utime - sensor.host0_us) - beam));
  }
  return errors;
}

// The goal: p99 < 1 ms, p50 < 0.3 ms. (At 0 ppm with a period of whole
// device milliseconds the stamp's phase is hidden: the error is that of the
// stamp's middle, constant and <= 0.5 ms.)
TEST(ClockModel, SubMillisecondWithDriftAndUniformDelay) {
  for (double drift : {100.0, -100.0, 37.0, 10.0, 0.0}) {
    for (unsigned seed : {1u, 2u}) {
      const Errors e = percentiles(run(drift, 60.0, seed));
      EXPECT_LT(e.p99, 1000.0) << drift << " ppm seed " << seed;
      if (drift != 0.0) {
        EXPECT_LT(e.p50, 300.0) << drift << " ppm seed " << seed;
      }
    }
  }
}

TEST(ClockModel, LearnsTheDriftFromTheScanStreamWithoutTm1) {
  // No TM1 after the first burst: the gain comes from the scans' minimum delay alone.
  for (double drift : {100.0, -100.0}) {
    std::vector<double> errors = run(drift, 120.0, 4, 0, false);
    const Errors late = percentiles(std::vector<double>(errors.end() - 1200, errors.end()));
    EXPECT_LT(late.p99, 1000.0) << drift;
  }
  ClockModel model;
  EXPECT_DOUBLE_EQ(model.drift_ppm(), 0.0);
}

TEST(ClockModel, TmAnsweredOnFiveMsTicks) {
  const Errors e = percentiles(run(-80.0, 60.0, 5, 5.0));
  EXPECT_LT(e.p99, 1000.0);
}

TEST(ClockModel, WithoutSyncAnchorsOnArrival) {
  ClockModel model;
  const int64_t utime = model.scan_utime(1000, 25000, 5'000'000);
  EXPECT_FALSE(model.synced());
  EXPECT_EQ(utime, 5'000'000);
  EXPECT_FALSE(model.sync({}));
}

}  // namespace
}  // namespace slamer::urg

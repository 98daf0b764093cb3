// slamer-urg-sim with scans from outside: the REP 117 -> SCIP value conversion
// and geometry checks (sim_scan_source.hpp), and the sensor sending a fed scan
// as the real one would: after its last requested beam, stamped by the device
// clock at its first, only while streaming, never before it arrived.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "drivers/urg/scip_codec.hpp"
#include "drivers/urg/scip_reply.hpp"
#include "drivers/urg/scip_scan.hpp"
#include "tools/urg_sim/sim_scan_source.hpp"

namespace slamer::urg {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int64_t kFeedStart = 1'700'000'000'000'000;

SimModel model(const std::string& name) {
  SimModel m;
  EXPECT_TRUE(sim_model(name, &m));
  return m;
}

// A scan with the URM-40LC geometry (slamer-sim's i-Cart mini LiDAR).
LaserScan urm_scan(int64_t utime) {
  LaserScan scan;
  scan.utime = utime;
  scan.angle_min = -0.75 * std::numbers::pi;
  scan.angle_increment = 2 * std::numbers::pi / 1440;
  scan.scan_period = 0.025f;
  scan.ranges.assign(1081, 1.0f);
  return scan;
}

TEST(SimScanFrom, RangesBecomeDeviceValuesAndErrorCodes) {
  LaserScan scan = urm_scan(kFeedStart);
  scan.ranges[0] = 1.2345f;        // 1234.50005 mm: 1235
  scan.ranges[1] = 3.2304999f;     // 3230 mm
  scan.ranges[2] = kInf;           // no return
  scan.ranges[3] = -kInf;          // too close
  scan.ranges[4] = std::nanf("");  // error
  scan.ranges[5] = 0.059f;         // below the URM-40LC's DMIN 60 mm: too near
  scan.ranges[6] = 30.0004f;       // 30000 mm = DMAX
  scan.ranges[7] = 30.2f;          // beyond DMAX: no object in range
  SimScan out;
  std::string error;
  ASSERT_TRUE(sim_scan_from(scan, model("URM-40LC"), kFeedStart + 19000, &out, &error)) << error;
  EXPECT_EQ(out.first_beam_us, kFeedStart);
  EXPECT_EQ(out.received_us, kFeedStart + 19000);
  ASSERT_EQ(out.values.size(), 1081u);
  EXPECT_EQ(out.values[0], 1235u);
  EXPECT_EQ(out.values[1], 3230u);
  EXPECT_EQ(out.values[2], 1u);
  EXPECT_EQ(out.values[3], 2u);
  EXPECT_EQ(out.values[4], 3u);
  EXPECT_EQ(out.values[5], 2u);
  EXPECT_EQ(out.values[6], 30000u);
  EXPECT_EQ(out.values[7], 1u);
  EXPECT_EQ(out.values[8], 1000u);
  EXPECT_TRUE(out.intensities.empty());
  // What the driver makes of them: the same REP 117 classes.
  SensorGeometry g;
  g.model = "URM-40LC-EW", g.dmin = 60, g.dmax = 30000;
  EXPECT_EQ(range_from_device(out.values[2], g), kInf);
  EXPECT_EQ(range_from_device(out.values[3], g), -kInf);
  EXPECT_TRUE(std::isnan(range_from_device(out.values[4], g)));
}

TEST(SimScanFrom, Urg04HasNoTooNearCode) {
  const SimErrorCodes codes = sim_error_codes(model("URG-04LX"));
  EXPECT_EQ(codes.no_echo, 0u);
  SensorGeometry g;
  g.model = "URG-04LX", g.dmin = 20, g.dmax = 5600;
  EXPECT_EQ(range_from_device(codes.no_echo, g), kInf);
  EXPECT_TRUE(std::isnan(range_from_device(codes.too_near, g)));
  EXPECT_TRUE(std::isnan(range_from_device(codes.error, g)));
}

TEST(SimScanFrom, AGeometryThatIsNotTheModelsIsRefusedWithAReason) {
  SimScan out;
  std::string error;
  LaserScan scan = urm_scan(kFeedStart);
  scan.ranges.resize(541);
  EXPECT_FALSE(sim_scan_from(scan, model("URM-40LC"), kFeedStart, &out, &error));
  EXPECT_NE(error.find("541 beams"), std::string::npos) << error;
  scan = urm_scan(kFeedStart);
  scan.angle_increment *= 2;
  EXPECT_FALSE(sim_scan_from(scan, model("URM-40LC"), kFeedStart, &out, &error));
  EXPECT_NE(error.find("angle increment"), std::string::npos) << error;
  scan = urm_scan(kFeedStart);
  scan.angle_min = -std::numbers::pi;
  EXPECT_FALSE(sim_scan_from(scan, model("URM-40LC"), kFeedStart, &out, &error));
  EXPECT_NE(error.find("angle_min"), std::string::npos) << error;
  scan = urm_scan(kFeedStart);
  scan.scan_period = 0.1f;
  EXPECT_FALSE(sim_scan_from(scan, model("URM-40LC"), kFeedStart, &out, &error));
  EXPECT_NE(error.find("scan period"), std::string::npos) << error;
  EXPECT_FALSE(sim_scan_from(urm_scan(kFeedStart), model("URG-04LX"), kFeedStart, &out, &error));  // 682 beams
}

// Frames the sensor's output and returns the scan replies (status 99).
std::vector<ScanData> scans_in(const std::string& bytes) {
  ReplyFramer framer;
  framer.feed(bytes);
  std::vector<std::string> lines;
  std::vector<ScanData> scans;
  while (framer.next(&lines)) {
    const Reply reply = parse_reply(lines);
    ScanData scan;
    if (reply.status == "99" && decode_scan(reply, &scan) == ScanError::kOk) {
      scans.push_back(scan);
    }
  }
  return scans;
}

TEST(SimSensorFeed, AFedScanIsSentAfterItsLastBeamStampedAtItsFirst) {
  SimKnobs knobs;
  knobs.external_scans = true;
  knobs.offset_ms = 1000.0;
  knobs.drift_ppm = 100.0;
  SimSensor sensor(model("URM-40LC"), knobs);
  sensor.power_on(kFeedStart);
  SimScan early;
  ASSERT_TRUE(sim_scan_from(urm_scan(kFeedStart + 5000), sensor.model(), kFeedStart + 6000, &early, nullptr));
  sensor.feed(early);  // not streaming yet: dropped
  sensor.receive("MD0000108001000\n", kFeedStart + 10000);
  EXPECT_EQ(sensor.poll(kFeedStart + 10000).substr(0, 21), "MD0000108001000\n00P\n\n");
  // A scan that began before the command: a real sensor only sends rotations measured after it.
  SimScan before;
  ASSERT_TRUE(sim_scan_from(urm_scan(kFeedStart + 9000), sensor.model(), kFeedStart + 26000, &before, nullptr));
  sensor.feed(before);
  LaserScan source = urm_scan(kFeedStart + 30000);
  source.ranges[100] = 2.5f;
  SimScan fed;
  ASSERT_TRUE(sim_scan_from(source, sensor.model(), kFeedStart + 45000, &fed, nullptr));
  sensor.feed(fed);
  EXPECT_TRUE(scans_in(sensor.poll(kFeedStart + 28000)).empty());  // the one from before the command is gone
  // The 1081 steps take 1081 / 1440 of 25 ms: the reply is ready 18767 us after the first beam.
  const int64_t ready = kFeedStart + 30000 + 18767;
  EXPECT_EQ(sensor.next_event_us(), ready);
  EXPECT_TRUE(scans_in(sensor.poll(ready - 1)).empty());
  const std::vector<ScanData> sent = scans_in(sensor.poll(ready));
  ASSERT_EQ(sent.size(), 1u);
  const double device_ms = 1000.0 + (1.0 + 100e-6) * 30.0;  // the device clock at the first beam
  EXPECT_EQ(sent[0].timestamp_ms, static_cast<uint32_t>(std::floor(device_ms)));
  ASSERT_EQ(sent[0].distances.size(), 1081u);
  EXPECT_EQ(sent[0].distances[100], 2500u);
  EXPECT_EQ(sent[0].distances[0], 1000u);
  const std::vector<SimTruth> truth = sensor.take_truth();
  ASSERT_EQ(truth.size(), 1u);
  EXPECT_EQ(truth[0].first_beam_host_us, kFeedStart + 30000);
  EXPECT_EQ(sensor.next_event_us(), INT64_MAX);  // no scene scans in between
}

TEST(SimSensorFeed, AScanArrivingLateIsSentWhenItArrivesWithIntensitiesForMe) {
  SimKnobs knobs;
  knobs.external_scans = true;
  SimSensor sensor(model("URM-40LC"), knobs);
  sensor.power_on(kFeedStart);
  sensor.receive("ME0000108001000\n", kFeedStart);
  sensor.poll(kFeedStart);
  LaserScan source = urm_scan(kFeedStart + 25000);
  source.intensities.assign(1081, 0.0f);
  source.intensities[7] = 1234.0f;
  SimScan fed;
  ASSERT_TRUE(sim_scan_from(source, sensor.model(), kFeedStart + 60000, &fed, nullptr));
  sensor.feed(fed);
  EXPECT_EQ(sensor.next_event_us(), kFeedStart + 60000);  // ready at 43767 us, but it only arrived at 60000
  const std::vector<ScanData> sent = scans_in(sensor.poll(kFeedStart + 60000));
  ASSERT_EQ(sent.size(), 1u);
  ASSERT_EQ(sent[0].intensities.size(), 1081u);
  EXPECT_EQ(sent[0].intensities[7], 1234u);
  EXPECT_EQ(sent[0].intensities[8], 0u);
}

}  // namespace
}  // namespace slamer::urg

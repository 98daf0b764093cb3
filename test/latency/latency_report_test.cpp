// LatencyRecorder: matching objects and poses to their scans by utime,
// percentiles, lost scans from seq gaps, restarted processes' counters.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tools/latency/latency_report.hpp"

namespace slamer {
namespace {

TEST(LatencyRecorder, MatchesByUtimeAndCountsWhatIsMissing) {
  LatencyRecorder r;
  constexpr int64_t t0 = 1'700'000'000'000'000;
  constexpr double kSweep = 0.01875;  // 270 deg of a 40 Hz sweep
  // 100 scans, seq 0..104 with 5 skipped; on the bus 20 ms after the first beam,
  // objects 25 ms, poses 30 ms (the 100th 80 ms); scan 10 has no objects, scan 20 no pose.
  int64_t seq = 0;
  for (int i = 0; i < 100; ++i, ++seq) {
    if (i == 50) {
      seq += 5;
    }
    const int64_t utime = t0 + 25'000 * i;
    r.on_scan(utime, seq, kSweep, utime + 20'000);
    if (i != 10) {
      r.on_objects(utime, utime + 25'000);
    }
    if (i != 20) {
      r.on_pose(utime, utime + (i == 99 ? 80'000 : 30'000));
    }
  }
  r.on_scan(t0, 0, kSweep, t0 + 99'000);  // a duplicate: ignored
  r.on_pose(t0 - 25'000, t0);             // for a scan before the log started
  r.on_objects(t0 + 1, t0 + 2);

  const LatencyReport report = r.report();
  EXPECT_EQ(report.scans, 100);
  EXPECT_NEAR(report.duration_s, 99 * 0.025, 1e-9);
  EXPECT_EQ(report.scans_lost_before_bus, 5);
  EXPECT_EQ(report.scans_without_objects, 1);
  EXPECT_EQ(report.scans_without_pose, 1);
  EXPECT_EQ(report.unmatched_poses, 1);
  EXPECT_EQ(report.unmatched_objects, 1);
  EXPECT_EQ(report.lidar.count, 100);
  EXPECT_NEAR(report.lidar.p50_ms, 20.0, 1e-9);
  EXPECT_NEAR(report.objects.p99_ms, 25.0, 1e-9);
  EXPECT_EQ(report.pose.count, 99);
  EXPECT_NEAR(report.pose.p50_ms, 30.0, 1e-9);
  EXPECT_NEAR(report.pose.p99_ms, 80.0, 1e-9);  // nearest rank: of 99 samples, the 99th percentile is the largest
  EXPECT_NEAR(report.pose.max_ms, 80.0, 1e-9);
  EXPECT_NEAR(report.pose_after_last_beam.p50_ms, 30.0 - kSweep * 1e3, 1e-6);

  const nlohmann::json j = nlohmann::json::parse(render_json(report));
  EXPECT_EQ(j.at("scans_without_pose").get<int>(), 1);
  EXPECT_NEAR(j.at("pose").at("max_ms").get<double>(), 80.0, 1e-9);
  EXPECT_NE(render_text(report).find("first beam -> POSE"), std::string::npos);
}

TEST(LatencyRecorder, ARestartedProcessesCountersAreAddedUp) {
  LatencyRecorder r;
  ProcessTotals first;
  first.messages_in = 100;
  first.drops = 2;
  first.processing_p99_ms = 4.0;
  r.on_status("slamer-localizer", 10, first);
  first.messages_in = 200;  // its last status counts
  r.on_status("slamer-localizer", 10, first);
  ProcessTotals second;
  second.messages_in = 50;
  second.drops = 1;
  second.processing_p99_ms = 3.0;
  r.on_status("slamer-localizer", 11, second);
  ProcessTotals other;
  other.messages_out = 7;
  r.on_status("slamer-urg", 12, other);

  const LatencyReport report = r.report();
  ASSERT_EQ(report.processes.size(), 2u);
  const ProcessTotals& localizer = report.processes[0];
  EXPECT_EQ(localizer.process, "slamer-localizer");
  EXPECT_EQ(localizer.pids, 2);
  EXPECT_EQ(localizer.messages_in, 250);
  EXPECT_EQ(localizer.drops, 3);
  EXPECT_DOUBLE_EQ(localizer.processing_p99_ms, 4.0);
  EXPECT_EQ(report.processes[1].messages_out, 7);
  EXPECT_EQ(report.scans, 0);
  EXPECT_EQ(report.pose.count, 0);
}

}  // namespace
}  // namespace slamer

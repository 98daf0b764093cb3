// slamer-bench's scoring: one pose per scan, errors, the status-versus-error
// table and the files it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/config/config_reader.hpp"
#include "common/process/command_line.hpp"
#include "tools/datasets/bench_files.hpp"
#include "tools/datasets/bench_scoring.hpp"
#include "tools/datasets/settling.hpp"

namespace slamer {
namespace {

TEST(BenchScoring, OnePosePerScanAndTheConfusionTable) {
  const std::vector<int64_t> utimes{100, 200, 300, 400};
  const std::vector<int64_t> log_times{5'000'000, 5'000'000, 6'000'000, 7'000'000};  // the log's own clock
  const std::vector<PoseReport> reports{{400, {3.0, 0.0, 0.0}, BenchStatus::kLost},
                                        {200, {1.0, 0.0, 0.1}, BenchStatus::kOk}};
  int64_t missing = 0;
  const auto poses = poses_per_scan(utimes, log_times, reports, {0.5, 0.0, 0.0}, &missing);
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_EQ(missing, 2);
  EXPECT_EQ(poses[0].status, BenchStatus::kInitializing);  // before any POSE: the initial pose
  EXPECT_DOUBLE_EQ(poses[0].pose.x, 0.5);
  EXPECT_FALSE(poses[2].has_report);  // repeats scan 1's pose
  EXPECT_DOUBLE_EQ(poses[2].pose.x, 1.0);
  EXPECT_EQ(poses[2].status, BenchStatus::kOk);
  EXPECT_DOUBLE_EQ(poses[2].t, 6.0);
  const std::vector<Pose2> reference{{0.5, 0.0, 0.0}, {1.0, 0.1, 0.0}, {1.3, 0.0, 0.0}, {2.0, 0.0, 0.0}};
  const BenchScore score = score_poses(poses, reference);
  EXPECT_NEAR(score.position.mean, (0.0 + 0.1 + 0.3 + 1.0) / 4, 1e-12);
  EXPECT_NEAR(score.position.max, 1.0, 1e-12);
  EXPECT_NEAR(score.heading.max, 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(score.fraction_lost, 0.25);
  EXPECT_EQ(score.confusion[0][0], 1);  // INITIALIZING, < 0.2 m
  EXPECT_EQ(score.confusion[1][0], 1);  // OK, < 0.2 m
  EXPECT_EQ(score.confusion[1][1], 1);  // OK, 0.2-0.5 m
  EXPECT_EQ(score.confusion[3][2], 1);  // LOST, > 0.5 m
  const std::string text = format_poses(poses);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
  EXPECT_EQ(text.substr(0, text.find('\n')), "5.000000 0.5000 0.0000 0.00000 INITIALIZING");
  const auto json = nlohmann::json::parse(
      summary_json(score, {"x.log", "lfm", 500, "all", 1, 2.0, 1.0, "cmd", 0.4, false, std::nullopt}));
  EXPECT_DOUBLE_EQ(json["fraction_lost"].get<double>(), 0.25);
  EXPECT_EQ(json["status_vs_error"]["LOST"]["error_above_0.5m"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(json["time_per_scan_ms"]["cpu"].get<double>(), 250.0);
  EXPECT_NEAR(json["time_per_scan_ms"]["cpu_without_startup"].get<double>(), 200.0, 1e-9);  // 0.6 s over 3 scans
  const std::string png = (std::filesystem::temp_directory_path() / "slamer_bench_plot.png").string();
  write_bench_plot(poses, score, "test", png);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  std::filesystem::remove(png);
  EXPECT_THROW(score_poses(poses, {}), std::invalid_argument);
}

TEST(BenchScoring, StatusHonestyExcusesTheFirstTwoSecondsOfEachStretchFarOff) {
  // 10 Hz by utime (the log's own time frozen, as csail's); far off (1 m) from 1.0 s to 4.9 s and
  // again from 6.0 s to 6.9 s.
  std::vector<BenchPose> poses;
  std::vector<Pose2> reference;
  for (int k = 0; k < 80; ++k) {
    const bool far = (k >= 10 && k < 50) || (k >= 60 && k < 70);
    // OK for the first 3 s of the first stretch (1 s too long), then UNCERTAIN; the
    // second stretch never flagged, but shorter than the grace; LOST once while close.
    const BenchStatus status =
        k >= 40 && k < 50 ? BenchStatus::kUncertain : (k == 75 ? BenchStatus::kLost : BenchStatus::kOk);
    poses.push_back({1e9, {far ? 1.0 : 0.05, 0.0, 0.0}, status, true, 100'000 * int64_t{k}});
    reference.push_back({0.0, 0.0, 0.0});
  }
  const StatusHonesty h = score_poses(poses, reference).honesty;
  EXPECT_EQ(h.far_after_grace(), 20);  // 3.0-4.9 s; the second stretch is all grace
  EXPECT_EQ(h.far_after_grace_flagged(), 10);
  EXPECT_DOUBLE_EQ(h.far_flagged_fraction(), 0.5);
  EXPECT_EQ(h.close(), 30);
  EXPECT_EQ(h.close_lost(), 1);
  EXPECT_NEAR(h.close_lost_fraction(), 1.0 / 30.0, 1e-12);
  EXPECT_EQ(h.close_not_ok(), 1);  // the LOST one; the UNCERTAIN ones are far
  EXPECT_DOUBLE_EQ(StatusHonesty{}.far_flagged_fraction(), 1.0);
  // A message's status field: the four values, nothing else.
  EXPECT_EQ(reported_status(2), ReportedStatus::kUncertain);
  EXPECT_EQ(reported_status(0), ReportedStatus::kInitializing);
  EXPECT_FALSE(reported_status(4).has_value());
  EXPECT_FALSE(reported_status(-1).has_value());
  const auto json = nlohmann::json::parse(summary_json(score_poses(poses, reference), {}));
  EXPECT_DOUBLE_EQ(json["status_honesty"]["far_flagged_fraction"].get<double>(), 0.5);
}

TEST(BenchScoring, RightFromAfterTheLastStretchFarOffForTwoSecondsAndOkFromTheFirstOkAfterThat) {
  // 10 Hz by utime (the log's own time frozen, as csail's): 2 m off for the first 2.5 s, 0.8 m
  // for one scan at 3.0 s (a blip: under 1 m, under 2 s), else 0.4 m; OK from 1.0 s to 1.9 s
  // (while far off), UNCERTAIN from 2.0 s to 3.9 s, OK from 4.0 s.
  std::vector<BenchPose> poses;
  std::vector<Pose2> reference;
  for (int k = 0; k < 60; ++k) {
    const double error = k < 25 ? 2.0 : (k == 30 ? 0.8 : 0.4);
    const bool ok = (k >= 10 && k < 20) || k >= 40;
    poses.push_back({1e9,
                     {error, 0.0, 0.0},
                     ok ? BenchStatus::kOk : BenchStatus::kUncertain,
                     true,
                     5'000'000 + 100'000 * int64_t{k}});
    reference.push_back({0.0, 0.0, 0.0});
  }
  BenchScore score = score_poses(poses, reference);
  ASSERT_TRUE(score.right_from.has_value());
  EXPECT_EQ(*score.right_from, 25);
  EXPECT_NEAR(score.right_from_seconds, 2.5, 1e-9);
  EXPECT_EQ(score.far_after_right, 1);
  ASSERT_TRUE(score.ok_from.has_value());
  EXPECT_EQ(*score.ok_from, 40);
  EXPECT_NEAR(score.ok_from_seconds, 4.0, 1e-9);
  EXPECT_EQ(score.confusion[1][2], 10);  // OK while 2 m off: 1.0-1.9 s
  const auto json = nlohmann::json::parse(summary_json(score, {}));
  EXPECT_EQ(json["right_from"]["scan"].get<int>(), 25);
  EXPECT_EQ(json["right_from"]["ok_scan"].get<int>(), 40);
  EXPECT_EQ(json["right_from"]["far_scans_after"].get<int>(), 1);
  // Off at the last scan, if only for one: never right, never OK.
  poses.back().pose.x = 0.6;
  score = score_poses(poses, reference);
  EXPECT_FALSE(score.right_from.has_value());
  EXPECT_FALSE(score.ok_from.has_value());
  EXPECT_TRUE(nlohmann::json::parse(summary_json(score, {}))["right_from"]["scan"].is_null());
  // Off for only 1.5 s from the first scan (a search, not a blip): right from the scan after it;
  // right but never OK after.
  for (std::size_t k = 0; k < poses.size(); ++k) {
    poses[k].pose.x = k < 15 ? 2.0 : (k == 30 ? 0.8 : 0.1);
    poses[k].status = BenchStatus::kUncertain;
  }
  score = score_poses(poses, reference);
  EXPECT_EQ(score.right_from.value_or(-1), 15);
  EXPECT_EQ(score.far_after_right, 1);
  EXPECT_FALSE(score.ok_from.has_value());
  // One scan 1.5 m off is another place, not a blip.
  poses[30].pose.x = 1.5;
  score = score_poses(poses, reference);
  EXPECT_EQ(score.right_from.value_or(-1), 31);
  EXPECT_EQ(score.far_after_right, 0);
  // Never off: right from the first scan.
  poses[30].pose.x = 0.1;
  for (std::size_t k = 0; k < 15; ++k) {
    poses[k].pose.x = 0.1;
  }
  score = score_poses(poses, reference);
  EXPECT_EQ(score.right_from.value_or(-1), 0);
  EXPECT_EQ(score.far_after_right, 0);
}

TEST(Settling, FromTheLastJumpOnceNineInTenSayOk) {
  // 10 Hz: uncertain and jumping about for 3 s, then one more jump at 4 s, then
  // smooth with one UNCERTAIN in every 20 poses.
  std::vector<PoseReport> poses;
  for (int k = 0; k < 100; ++k) {
    const bool searching = k < 30;
    const double x = searching ? (k % 2) * 5.0 : (k < 40 ? 10.0 : 20.0) + 0.01 * k;
    const BenchStatus status = searching || k % 20 == 7 ? BenchStatus::kUncertain : BenchStatus::kOk;
    poses.push_back({1'000'000 + 100'000 * k, {x, 1.0, 0.0}, status});
  }
  const Settling s = settling(poses);
  ASSERT_TRUE(s.scan.has_value());
  EXPECT_EQ(*s.scan, 40);  // the jump to x = 20
  EXPECT_NEAR(s.seconds, 4.0, 1e-9);
  EXPECT_NEAR(s.ok_fraction, 67.0 / 100.0, 1e-12);  // 70 after the search, 3 of them UNCERTAIN
  EXPECT_NEAR(s.end.x, 20.99, 1e-9);
  // UNCERTAIN from 60 on: no stretch to the end is 90 % OK once the last third says so.
  for (int k = 60; k < 100; ++k) {
    poses[static_cast<std::size_t>(k)].status = BenchStatus::kUncertain;
  }
  EXPECT_FALSE(settling(poses).scan.has_value());
  EXPECT_FALSE(settling({}).scan.has_value());
}

TEST(Settling, RunsAgreeFromTheScanAfterWhichAllStayWithinTheDistance) {
  // Three runs of one log at 10 Hz: the first two track together; the third is
  // elsewhere until scan 30, then joins them but strays 0.8 m at scan 50.
  std::vector<std::vector<PoseReport>> runs(3);
  for (int k = 0; k < 100; ++k) {
    const int64_t utime = 1'000'000 + 100'000 * k;
    const double x = 0.1 * k;
    runs[0].push_back({utime, {x, 0.0, 0.0}, BenchStatus::kOk});
    runs[1].push_back({utime, {x + 0.2, 0.0, 0.0}, BenchStatus::kOk});
    const double off = k < 30 ? 12.0 : (k == 50 ? 0.8 : -0.1);
    runs[2].push_back({utime, {x, off, 0.0}, BenchStatus::kUncertain});
  }
  runs[1].erase(runs[1].begin() + 70);  // a scan one run has no pose for is left out
  const Agreement a = agreement(runs, 0.5);
  EXPECT_EQ(a.scans, 99);
  ASSERT_TRUE(a.scan.has_value());
  EXPECT_EQ(*a.scan, 51);
  EXPECT_NEAR(a.seconds, 5.1, 1e-9);
  EXPECT_NEAR(a.spread_after, std::hypot(0.2, 0.1), 1e-9);  // the second run and the third
  EXPECT_NEAR(a.spread_at_end, std::hypot(0.2, 0.1), 1e-9);
  // Within 0.2 m never: the second run is 0.2 m ahead and the third 0.1 m aside.
  EXPECT_FALSE(agreement(runs, 0.2).scan.has_value());
  // Apart at the end: never, whatever came before.
  runs[2].back().pose.y = 3.0;
  const Agreement apart = agreement(runs, 0.5);
  EXPECT_FALSE(apart.scan.has_value());
  EXPECT_NEAR(apart.spread_at_end, std::hypot(0.2, 3.0), 1e-9);
  EXPECT_THROW(agreement({runs[0]}, 0.5), std::invalid_argument);
}

TEST(Settling, GroupsSayWhichRunsAgreeWhereNotAllDo) {
  // Four runs at 10 Hz: the second joins the first at scan 20 (0.3 m ahead), the
  // third is 10 m away throughout, the fourth 0.45 m beside the first and so 0.54 m
  // from the second: the first agrees with both, the three never all within 0.5 m.
  std::vector<std::vector<PoseReport>> runs(4);
  for (int k = 0; k < 50; ++k) {
    const int64_t utime = 1'000'000 + 100'000 * k;
    const double x = 0.1 * k;
    runs[0].push_back({utime, {x, 0.0, 0.0}, BenchStatus::kOk});
    runs[1].push_back({utime, {x + (k < 20 ? 10.0 : 0.3), 0.0, 0.0}, BenchStatus::kOk});
    runs[2].push_back({utime, {x, 10.0, 0.0}, BenchStatus::kOk});
    runs[3].push_back({utime, {x, -0.45, 0.0}, BenchStatus::kOk});
  }
  const std::vector<AgreeingGroup> three = agreeing_groups({runs[0], runs[1], runs[2]}, 0.5);
  ASSERT_EQ(three.size(), 2u);
  EXPECT_EQ(three[0].runs, (std::vector<std::size_t>{0, 1}));
  ASSERT_TRUE(three[0].agreement.scan.has_value());
  EXPECT_EQ(*three[0].agreement.scan, 20);
  EXPECT_NEAR(three[0].agreement.seconds, 2.0, 1e-9);
  EXPECT_EQ(three[1].runs, (std::vector<std::size_t>{2}));
  EXPECT_FALSE(three[1].agreement.scan.has_value());

  const std::vector<AgreeingGroup> four = agreeing_groups(runs, 0.5);
  ASSERT_EQ(four.size(), 2u);
  EXPECT_EQ(four[0].runs, (std::vector<std::size_t>{0, 1, 3}));
  EXPECT_FALSE(four[0].agreement.scan.has_value());
  EXPECT_NEAR(four[0].agreement.spread_at_end, std::hypot(0.3, 0.45), 1e-9);
  EXPECT_EQ(four[1].runs, (std::vector<std::size_t>{2}));
}

TEST(BenchFiles, LocalizerConfigKeepsEverythingElse) {
  const std::string config = std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml");
  const std::string yaml = bench_localizer_config(config, {123, 3, "/m/map.yaml", "/r/robot.yaml"});
  EXPECT_NE(yaml.find("particles: 123"), std::string::npos);
  EXPECT_NE(yaml.find("beam_step: 3"), std::string::npos);
  EXPECT_NE(yaml.find("map: /m/map.yaml"), std::string::npos);
  EXPECT_NE(yaml.find("alpha_rot_from_trans"), std::string::npos);
  EXPECT_THROW(bench_localizer_config("/nonexistent.yaml", {}), ConfigError);
}

TEST(BenchFiles, AKidnapLeavesOutTheCarryAndTheOdometryMeasuresOnlyTheOrdinaryStep) {
  // 10 scans 100 ms apart on a line, 0.1 m apart; odometry 2 % long and turning 0.01 rad a step,
  // one pose at each scan and one half-way to the next.
  ImportedLog log;
  Pose2 odometry{5.0, -1.0, 0.3};
  const Pose2 step{0.102, 0.0, 0.01};
  for (int k = 0; k < 10; ++k) {
    LaserScan scan;
    scan.utime = 1'000'000 + 100'000 * k;
    scan.sensor_utime = 7'000'000 + 100'000 * k;
    scan.seq = k;
    log.scans.push_back(scan);
    log.reference.push_back({0.1 * k, 0.0, 0.0});
    log.scan_odometry.push_back(odometry);
    log.odometry.push_back({scan.utime, odometry, 1.0, 0.1});
    log.odometry.push_back({scan.utime + 50'000, compose(odometry, {0.051, 0.0, 0.005}), 1.0, 0.1});
    odometry = compose(odometry, step);
  }
  const ImportedLog out = kidnapped(log, 3, 7);  // carried from scan 3 to scan 7
  ASSERT_EQ(out.scans.size(), 6u);
  ASSERT_EQ(out.reference.size(), 6u);
  ASSERT_EQ(out.scan_odometry.size(), 6u);
  EXPECT_EQ(out.scans[3].utime, 1'300'000);  // one period after scan 2
  EXPECT_EQ(out.scans[3].sensor_utime, 7'700'000);
  EXPECT_EQ(out.scans[3].seq, 3);
  EXPECT_EQ(out.scans[5].utime, 1'500'000);
  EXPECT_DOUBLE_EQ(out.reference[3].x, 0.7);
  // Every step the odometry measures is an ordinary one: the carry of 0.4 m is unseen.
  for (std::size_t k = 1; k < out.scans.size(); ++k) {
    const Pose2 measured = between(out.scan_odometry[k - 1], out.scan_odometry[k]);
    EXPECT_NEAR(measured.x, step.x, 1e-9) << k;
    EXPECT_NEAR(measured.y, step.y, 1e-9) << k;
    EXPECT_NEAR(measured.theta, step.theta, 1e-9) << k;
  }
  // The stream: scans 0-2 and their half-way poses kept; from scan 7 on, earlier by 0.4 s and
  // re-anchored to the scans' odometry; strictly increasing.
  ASSERT_EQ(out.odometry.size(), 12u);
  EXPECT_EQ(out.odometry[6].utime, 1'300'000);
  EXPECT_NEAR(out.odometry[6].pose.x, out.scan_odometry[3].x, 1e-9);
  EXPECT_NEAR(out.odometry[6].pose.theta, out.scan_odometry[3].theta, 1e-9);
  const Pose2 half = between(out.odometry[6].pose, out.odometry[7].pose);
  EXPECT_NEAR(half.x, 0.051, 1e-9);
  for (std::size_t k = 1; k < out.odometry.size(); ++k) {
    EXPECT_LT(out.odometry[k - 1].utime, out.odometry[k].utime);
  }
  EXPECT_THROW(kidnapped(log, 0, 5), std::invalid_argument);
  EXPECT_THROW(kidnapped(log, 5, 5), std::invalid_argument);
  EXPECT_THROW(kidnapped(log, 5, 10), std::invalid_argument);
  log.scan_odometry.pop_back();
  EXPECT_THROW(kidnapped(log, 3, 7), std::invalid_argument);
  EXPECT_EQ(describe_kidnap(log, out, 3),
            "kidnap: scans 3-6 left out; at scan 3 (0.3 s into the run) the robot was carried 0.4 m and 0 deg unseen");
}

TEST(BenchFiles, PosesOfAKidnappedRunCoverTheWholeLogTheCarriedScansRepeatingThePoseBefore) {
  ImportedLog whole;
  for (int k = 0; k < 6; ++k) {
    LaserScan scan;
    scan.utime = 1'000'000 + 100'000 * k;
    scan.sensor_utime = 7'000'000 + 100'000 * k;
    whole.scans.push_back(scan);
  }
  // Scans 2 and 3 carried: four poses kept, for scans 0, 1, 4 and 5.
  std::vector<BenchPose> kept;
  for (int k : {0, 1, 4, 5}) {
    BenchPose p;
    p.t = 7.0 + 0.1 * k;
    p.pose = {static_cast<double>(k), 0.0, 0.0};
    p.status = k == 1 ? BenchStatus::kUncertain : BenchStatus::kOk;
    kept.push_back(p);
  }
  const std::vector<BenchPose> all = with_carried_scans(kept, whole, 2, 4);
  ASSERT_EQ(all.size(), 6u);
  for (std::size_t k = 0; k < all.size(); ++k) {
    EXPECT_NEAR(all[k].t, 7.0 + 0.1 * static_cast<double>(k), 1e-9) << k;
  }
  for (std::size_t k : {2u, 3u}) {
    EXPECT_DOUBLE_EQ(all[k].pose.x, 1.0) << k;
    EXPECT_EQ(all[k].status, BenchStatus::kUncertain) << k;
    EXPECT_FALSE(all[k].has_report) << k;
  }
  EXPECT_DOUBLE_EQ(all[4].pose.x, 4.0);
  EXPECT_TRUE(all[4].has_report);
  EXPECT_THROW(with_carried_scans(kept, whole, 2, 5), std::invalid_argument);
  EXPECT_THROW(with_carried_scans(kept, whole, 0, 2), std::invalid_argument);
}

TEST(BenchFiles, LocalizerArgumentsStartAtTheReferencePoseOrGloballyAndKidnapScansAreChecked) {
  BenchLocalizerRun run{"/d/localizer.yaml", "/d/map.yaml", "/d/robot.yaml", "lfm", "3", Pose2{1.5, -2.0, 0.25}};
  const std::vector<std::string> from_pose = bench_localizer_args(run, "in.lcm", "out.lcm");
  const std::vector<std::string> expected{"--config",       "/d/localizer.yaml",
                                          "--map",          "/d/map.yaml",
                                          "--robot",        "/d/robot.yaml",
                                          "--initial-pose", "1.500000",
                                          "-2.000000",      "0.250000",
                                          "--mode",         "lfm",
                                          "--seed",         "3",
                                          "--replay",       "in.lcm",
                                          "--out",          "out.lcm"};
  EXPECT_EQ(from_pose, expected);
  run.start.reset();
  const std::vector<std::string> global = bench_localizer_args(run, "in.lcm", "out.lcm");
  ASSERT_EQ(global.size(), 15u);
  EXPECT_EQ(global[6], "--global");
  EXPECT_EQ(std::count(global.begin(), global.end(), "--initial-pose"), 0);
  EXPECT_EQ(kidnap_scans({40.0, 90.0}, 150), (std::pair<std::size_t, std::size_t>{40, 90}));
  EXPECT_THROW(kidnap_scans({0.0, 90.0}, 150), CommandLineError);
  EXPECT_THROW(kidnap_scans({90.0, 40.0}, 150), CommandLineError);
  EXPECT_THROW(kidnap_scans({40.0, 150.0}, 150), CommandLineError);
  EXPECT_THROW(kidnap_scans({40.5, 90.0}, 150), CommandLineError);
}

}  // namespace
}  // namespace slamer

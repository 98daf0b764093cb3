#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "tools/eval/evaluation.hpp"
#include "tools/eval/report.hpp"

namespace slamer {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PoseAt, InterpolatesInsideAndRefusesOutside) {
  const std::vector<PoseSample> series{{100, {0.0, 0.0, 0.0}}, {200, {1.0, 0.0, 0.0}}, {300, {1.0, 0.0, kPi / 2}}};
  EXPECT_FALSE(pose_at(series, 99).has_value());
  EXPECT_FALSE(pose_at(series, 301).has_value());
  EXPECT_NEAR(pose_at(series, 150)->x, 0.5, 1e-12);
  EXPECT_NEAR(pose_at(series, 250)->theta, kPi / 4, 1e-12);
  EXPECT_DOUBLE_EQ(pose_at(series, 300)->theta, kPi / 2);
  EXPECT_FALSE(pose_at({}, 5).has_value());
}

TEST(PoseErrors, StatisticsAndLostFraction) {
  std::vector<PoseSample> truth;
  std::vector<PoseSample> estimate;
  for (int i = 0; i < 10; ++i) {
    truth.push_back({i * 1000, {static_cast<double>(i), 0.0, kPi - 0.01}});
    // Eight estimates 0.1 m off, two 1.0 m off; headings 0.02 rad off across the +-pi seam.
    const double offset = i < 8 ? 0.1 : 1.0;
    estimate.push_back({i * 1000, {static_cast<double>(i), offset, -kPi + 0.01}});
  }
  estimate.push_back({50'000, {}});  // outside the ground truth: not scored
  const std::vector<PoseError> errors = pose_errors(truth, estimate);
  ASSERT_EQ(errors.size(), 10u);
  const PoseErrorStats stats = summarize(errors, 0.5);
  EXPECT_NEAR(stats.position_mean, 0.28, 1e-12);
  EXPECT_NEAR(stats.position_std, std::sqrt((8 * 0.18 * 0.18 + 2 * 0.72 * 0.72) / 10), 1e-12);
  EXPECT_NEAR(stats.position_max, 1.0, 1e-12);
  EXPECT_NEAR(stats.heading_mean, 0.02, 1e-9);
  EXPECT_NEAR(stats.lost_fraction, 0.2, 1e-12);
}

// A 20 m x 10 m map at 0.1 m: a door at x = 10 (drawn closed), a fence at
// y = 2 and a no-entry line at y = 8.
SemanticMap make_map() {
  SemanticMap map;
  map.geometry = {200, 100, 0.1, {}};
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  map.classes = {{"door", {255, 0, 255}},
                 {"glass_door", {0, 255, 255}},
                 {"fence", {255, 128, 0}},
                 {"no_entry_line", {255, 0, 0}},
                 {"others", {0, 0, 0}}};
  for (int y = 40; y < 60; ++y) {
    map.labels[map.geometry.index(100, y)] = 0;
    map.occupancy[map.geometry.index(100, y)] = Occupancy::kOccupied;
  }
  for (int x = 20; x < 80; ++x) {
    map.labels[map.geometry.index(x, 20)] = 2;
    map.labels[map.geometry.index(x, 80)] = 3;
  }
  return map;
}

TEST(ObjectLabeler, TrueClassesFromTheWorldAtTheTime) {
  const SemanticMap map = make_map();
  WorldOptions options;
  DoorTruth door;
  door.near = {10.05, 5.0};
  door.changes = {{30.0, DoorState::kOpen}};
  options.doors = {door};
  const TrueWorld world(map, options, "test");
  const EvalOptions eval;
  const ObjectLabeler labeler(world, eval);
  const auto name = [&](int index) {
    return index < 0 ? std::string("none") : eval.classes[static_cast<std::size_t>(index)].name;
  };
  EXPECT_EQ(name(labeler.label({10.05, 4.2}, {10.05, 5.8}, 0.0)), "closed_door");
  EXPECT_EQ(name(labeler.label({10.05, 4.2}, {10.05, 5.8}, 31.0)), "open_door");
  // A doorway line drawn 0.1 m off the door cells is still that (open) door.
  EXPECT_EQ(name(labeler.label({10.15, 4.2}, {10.15, 5.8}, 31.0)), "open_door");
  EXPECT_EQ(name(labeler.label({2.5, 2.05}, {7.5, 2.05}, 0.0)), "fence");
  EXPECT_EQ(name(labeler.label({2.5, 8.05}, {7.5, 8.05}, 0.0)), "no_entry_line");
  EXPECT_EQ(name(labeler.label({14.0, 5.0}, {16.0, 5.0}, 0.0)), "free_space");
}

TEST(ScoreRun, ThreeMethodsAgainstTheTruth) {
  const SemanticMap map = make_map();
  WorldOptions truth_options;
  truth_options.doors = {{{10.05, 5.0}, DoorState::kOpen, {}}};  // drawn closed, really open
  const TrueWorld truth_world(map, truth_options, "test");
  const TrueWorld map_world(map, WorldOptions{}, "test");
  const EvalOptions eval;

  RunInputs run;
  // The robot stands at (5, 5) facing +x, exactly where the estimate says.
  run.truth = {{0, {5.0, 5.0, 0.0}}, {1'000'000, {5.0, 5.0, 0.0}}};
  run.estimate = run.truth;
  const std::vector<std::string> names{"open_door", "closed_door",   "open_glass_door", "closed_glass_door",
                                       "fence",     "no_entry_line", "free_space",      "others"};
  const auto probs = [&](const std::string& winner) {
    std::vector<float> p(names.size(), 0.02f);
    p[static_cast<std::size_t>(std::find(names.begin(), names.end(), winner) - names.begin())] = 0.86f;
    return p;
  };
  // Scan 1 (t = 0): the door (sensor frame x = 5.05) recognized open (right), the fence recognized as fence (right).
  LineObjectSet scan1{0, 0, names, {}};
  scan1.objects.push_back({LineKind::kSpatial, {5.05, -0.8}, {5.05, 0.8}, 0, probs("open_door"), -1});
  scan1.objects.push_back({LineKind::kPhysical, {-2.5, -2.95}, {2.5, -2.95}, 30, probs("fence"), -1});
  // Scan 2 (t = 1 s): the door recognized closed (wrong).
  LineObjectSet scan2{1'000'000, 1, names, {}};
  scan2.objects.push_back({LineKind::kPhysical, {5.05, -0.8}, {5.05, 0.8}, 10, probs("closed_door"), -1});
  run.recognized = {scan1, scan2};
  // SLAMER says open door and fence in scan 1, open door in scan 2.
  LineObjectSet s1{0, 0, names, {}};
  s1.objects = {{LineKind::kSpatial, {}, {}, 0, probs("open_door"), 0},
                {LineKind::kPhysical, {}, {}, 0, probs("fence"), 4}};
  LineObjectSet s2{1'000'000, 1, names, {}};
  s2.objects = {{LineKind::kSpatial, {}, {}, 0, probs("open_door"), 0}};
  run.semantic = {s1, s2};

  const RunScores scores = score_run(run, truth_world, map_world, Pose2{}, eval);
  EXPECT_EQ(scores.recognizer.scans, 2u);
  EXPECT_EQ(scores.recognizer.objects, 3u);
  EXPECT_DOUBLE_EQ(scores.recognizer.mean, 0.5);  // scan 1: 2/2, scan 2: 0/1
  EXPECT_DOUBLE_EQ(scores.recognizer.min, 0.0);
  EXPECT_DOUBLE_EQ(scores.recognizer.max, 1.0);
  EXPECT_DOUBLE_EQ(scores.recognizer.std, 0.5);
  // The map shows the door closed: map-based gets the fence only.
  EXPECT_DOUBLE_EQ(scores.map_based.mean, (0.5 + 0.0) / 2);
  EXPECT_DOUBLE_EQ(scores.slamer.mean, 1.0);
  EXPECT_EQ(scores.pose.samples, 2u);
  EXPECT_DOUBLE_EQ(scores.pose.position_max, 0.0);
  // Where the map differs (the door, in both scans): recognizer 1/1 then 0/1, the map never, SLAMER always.
  EXPECT_EQ(scores.recognizer_differs.scans, 2u);
  EXPECT_DOUBLE_EQ(scores.recognizer_differs.mean, 0.5);
  EXPECT_DOUBLE_EQ(scores.map_based_differs.mean, 0.0);
  EXPECT_DOUBLE_EQ(scores.slamer_differs.mean, 1.0);
  // Confusion rows: open_door (0) and fence (4); columns as predicted.
  EXPECT_EQ(scores.recognizer_confusion.counts[0][0], 1);
  EXPECT_EQ(scores.recognizer_confusion.counts[0][1], 1);
  EXPECT_EQ(scores.recognizer_confusion.counts[4][4], 1);
  EXPECT_EQ(scores.map_based_confusion.counts[0][1], 2);
  EXPECT_EQ(scores.map_based_confusion.counts[4][4], 1);
  EXPECT_EQ(scores.slamer_confusion.counts[0][0], 2);
  EXPECT_EQ(scores.slamer_confusion.counts[1][1], 0);

  const std::string table = render_table({{"run.lcm", scores}}, eval);
  EXPECT_NE(table.find("50.00 %"), std::string::npos) << table;
  EXPECT_NE(table.find("100.00 %"), std::string::npos) << table;
  const nlohmann::json json = nlohmann::json::parse(render_json({{"run.lcm", scores}}, eval));
  const nlohmann::json& scored = json.at("runs").at(0);
  EXPECT_EQ(scored.at("name"), "run.lcm");
  EXPECT_EQ(scored.at("recognizer").at("scans"), 2);
  EXPECT_EQ(scored.at("recognizer").at("objects"), 3);
  EXPECT_DOUBLE_EQ(scored.at("recognizer").at("mean").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(scored.at("slamer").at("mean").get<double>(), 1.0);
}

TEST(ScoreRun, MissingChannelsAreNotApplicable) {
  const SemanticMap map = make_map();
  const TrueWorld world(map, WorldOptions{}, "test");
  const RunScores scores = score_run(RunInputs{}, world, world, Pose2{}, EvalOptions{});
  EXPECT_EQ(scores.pose.samples, 0u);
  const std::string table = render_table({{"empty.lcm", scores}}, EvalOptions{});
  EXPECT_NE(table.find("n/a"), std::string::npos);
  EXPECT_EQ(table.find("nan"), std::string::npos);
  const nlohmann::json json = nlohmann::json::parse(render_json({{"empty.lcm", scores}}, EvalOptions{}));
  EXPECT_TRUE(json.at("runs").at(0).at("pose").is_null());
  EXPECT_TRUE(json.at("runs").at(0).at("slamer").is_null());
  EXPECT_TRUE(json.at("runs").at(0).at("status_honesty").is_null());
}

// Scans every 0.3 s; the estimate is 1 m off from 3.0 s to 8.7 s (20 scans),
// saying OK until 5.7 s and UNCERTAIN from 6.0 s; back on the truth from 9.0 s,
// saying LOST at 9.0 and 9.3 s. From 2 s after the error passed 0.5 m (5.1 s
// on: 13 scans) 10 say UNCERTAIN; of the 20 close scans 2 say LOST.
TEST(ScoreRun, TheStatusIsScoredAgainstTheErrorFromTwoSecondsAfterItPassedHalfAMetre) {
  const SemanticMap map = make_map();
  const TrueWorld world(map, WorldOptions{}, "test");
  RunInputs run;
  for (int k = 0; k < 40; ++k) {
    const int64_t utime = 300'000LL * k;
    run.truth.push_back({utime, {2.0, 2.0, 0.0}, ReportedStatus::kOk});
    const bool far = k >= 10 && k < 30;
    const ReportedStatus status = far ? (k >= 20 ? ReportedStatus::kUncertain : ReportedStatus::kOk)
                                      : (k == 30 || k == 31 ? ReportedStatus::kLost : ReportedStatus::kOk);
    run.estimate.push_back({utime, {far ? 3.0 : 2.0, 2.0, 0.0}, status});
  }
  const RunScores scores = score_run(run, world, world, Pose2{}, EvalOptions{});
  ASSERT_TRUE(scores.honesty.has_value());
  EXPECT_EQ(scores.honesty->far_after_grace(), 13);
  EXPECT_EQ(scores.honesty->far_after_grace_flagged(), 10);
  EXPECT_EQ(scores.honesty->close(), 20);
  EXPECT_EQ(scores.honesty->close_lost(), 2);
  const std::string table = render_table({{"run.lcm", scores}}, EvalOptions{});
  EXPECT_NE(table.find("76.9 % of 13"), std::string::npos) << table;
  EXPECT_NE(table.find("10.00 / 10.00"), std::string::npos) << table;
  const nlohmann::json json = nlohmann::json::parse(render_json({{"run.lcm", scores}}, EvalOptions{}));
  EXPECT_NEAR(json.at("runs").at(0).at("status_honesty").at("far_flagged_fraction").get<double>(), 10.0 / 13.0, 1e-12);

  // Dead reckoning says nothing of itself: no status figures.
  for (PoseSample& s : run.estimate) {
    s.status.reset();
  }
  EXPECT_FALSE(score_run(run, world, world, Pose2{}, EvalOptions{}).honesty.has_value());
}

}  // namespace
}  // namespace slamer

// Local scan matching (localizer/local_match.hpp): from a prediction off by
// what a failing odometry gives, the search finds the pose the scan was taken
// at; beyond its window it does not reach; with nothing to match it keeps the
// prediction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/config/config_reader.hpp"
#include "localizer/local_match.hpp"
#include "localizer/localizer_options.hpp"
#include "localizer/particle_filter.hpp"
#include "recognizer/recognizer_options.hpp"
#include "test/localizer/options_error.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

class LocalMatchTest : public ::testing::Test {
 protected:
  SmallWorld w;
  LikelihoodField field{std::make_shared<const DistanceField>(obstacle_distance_field(w.map, 1.2)), {}};
};

// How matches and proposals score a pose: every step-th point's cell, placed
// as the beams are, summed; a point off the map at the off-map value.
TEST_F(LocalMatchTest, FieldLogLikelihoodSumsEveryStepthPointsCellOnAndOffTheMap) {
  const ScanPoints points = end_points(w.scan_at({2.0, 3.0, 0.3}), w.map.geometry.resolution);
  ASSERT_GT(points.x.size(), 300u);
  const LikelihoodField::Cells cells = field.cells();
  int off_map = 0;
  // In the room, and near its corner, where part of the scan falls off the map.
  for (const Pose2& sensor : {Pose2{40.0, 60.0, 0.3}, Pose2{3.0, 2.0, -2.5}}) {
    const auto c = static_cast<float>(std::cos(sensor.theta)), s = static_cast<float>(std::sin(sensor.theta));
    for (const std::size_t step : {1, 2, 3, 7, 1000}) {
      double expected = 0.0;
      for (std::size_t i = 0; i < points.x.size(); i += step) {
        const float gx = c * points.x[i] - s * points.y[i] + static_cast<float>(sensor.x);
        const float gy = s * points.x[i] + c * points.y[i] + static_cast<float>(sensor.y);
        expected += cells(gx, gy);
        off_map += cells(gx, gy) == field.off_map_log_likelihood() ? 1 : 0;
      }
      EXPECT_NEAR(field_log_likelihood(field, thinned_points(points, step), sensor), expected, 1e-9) << "step " << step;
    }
  }
  EXPECT_GT(off_map, 20);
}

TEST_F(LocalMatchTest, FindsThePoseFromAPredictionOffByAFailingOdometrysError) {
  const Pose2 truth{2.0, 3.0, 0.3};
  const ScanPoints points = end_points(w.scan_at(truth), w.map.geometry.resolution);
  // A sign of translation lost over 0.3 m, a turn measured 15 deg short, both.
  for (const Pose2& off : {Pose2{0.3, 0.0, 0.0}, Pose2{0.0, 0.0, -0.26}, Pose2{-0.25, 0.2, 0.35}}) {
    const Pose2 predicted = compose(truth, off);
    const LocalMatch m = match_locally(field, points, w.robot.lidar.mount, predicted, {});
    EXPECT_NEAR(m.pose.x, truth.x, 0.05) << off.x << " " << off.y << " " << off.theta;
    EXPECT_NEAR(m.pose.y, truth.y, 0.05) << off.x << " " << off.y << " " << off.theta;
    EXPECT_NEAR(angle_diff(m.pose.theta, truth.theta), 0.0, 0.01) << off.x << " " << off.y << " " << off.theta;
    // Within a cell of the truth (the field's sigma_hit is 0.2 m), and it scores better than the prediction.
    const LocalMatch at_prediction = match_locally(field, points, w.robot.lidar.mount, predicted,
                                                   {.shift = 0.0, .turn = 0.0, .shift_step = 0.1, .turn_step = 0.025});
    EXPECT_GT(m.mean_log_likelihood, at_prediction.mean_log_likelihood + 0.1);
  }
}

// A corridor with posts every 0.4 m along both walls: a scan there fits every
// 0.4 m. The runner-up is the next such place, not the best one's shoulder,
// and it fits about as well (what makes the filter put particles at both).
TEST(LocalMatch, TheRunnerUpIsAnotherPlaceTheScanFitsNotTheBestOnesShoulder) {
  const auto wall = [](int x, int y) { return y == 0 || y == 59 || ((y == 1 || y == 58) && x % 8 < 2); };
  const SemanticMap map = grid_map(240, 60, wall);  // 12 m x 3 m
  const LikelihoodField corridor(std::make_shared<const DistanceField>(obstacle_distance_field(map, 1.2)), {});
  // The walls' cells within 4 m, seen from the sensor at (6.0, 1.5), heading 0.
  const Pose2 truth{6.0, 1.5, 0.0};
  ScanPoints points;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 240; ++x) {
      const double dx = (x + 0.5) * 0.05 - truth.x;
      const double dy = (y + 0.5) * 0.05 - truth.y;
      if (wall(x, y) && std::hypot(dx, dy) < 4.0) {
        points.x.push_back(static_cast<float>(dx / 0.05));
        points.y.push_back(static_cast<float>(dy / 0.05));
      }
    }
  }
  const LocalMatch m = match_locally(corridor, points, {}, {6.05, 1.5, 0.0}, {.beams = 400});
  EXPECT_NEAR(m.pose.x, truth.x, 0.05);
  EXPECT_NEAR(m.pose.y, truth.y, 0.05);
  EXPECT_NEAR(std::abs(m.runner_up.x - m.pose.x), 0.4, 0.06) << m.runner_up.x;
  EXPECT_NEAR(m.runner_up.y, truth.y, 0.05);
  EXPECT_NEAR(m.runner_up.theta, 0.0, 0.03);
  const LocalMatchWindow here{.shift = 0.0, .turn = 0.0, .beams = 400};
  const double other = match_locally(corridor, points, {}, m.runner_up, here).mean_log_likelihood;
  EXPECT_LE(other, m.mean_log_likelihood);
  EXPECT_GT(other, m.mean_log_likelihood - 0.1);
}

TEST_F(LocalMatchTest, StaysWithinItsWindow) {
  const Pose2 truth{2.0, 3.0, 0.0};
  const ScanPoints points = end_points(w.scan_at(truth), w.map.geometry.resolution);
  const Pose2 predicted{3.2, 3.0, 0.0};  // 1.2 m off: beyond a 0.5 m window
  const LocalMatch m = match_locally(field, points, w.robot.lidar.mount, predicted, {.shift = 0.5, .turn = 0.2});
  // The sensor's pose stays within the window; the base's within the window plus what
  // turning by up to 0.2 rad moves the base about a sensor mounted 0.15 m ahead of it.
  const double slack = 0.15 * 0.2 + 1e-6;
  EXPECT_LE(std::abs(m.pose.x - predicted.x), 0.5 + slack);
  EXPECT_LE(std::abs(m.pose.y - predicted.y), 0.5 + slack);
  EXPECT_LE(std::abs(angle_diff(m.pose.theta, predicted.theta)), 0.2 + 1e-6);
  EXPECT_GT(std::abs(m.pose.x - truth.x), 0.3);
}

TEST_F(LocalMatchTest, WithoutPointsKeepsThePrediction) {
  const Pose2 predicted{2.0, 3.0, 0.5};
  const LocalMatch m = match_locally(field, {}, w.robot.lidar.mount, predicted, {});
  EXPECT_EQ(m.pose.x, predicted.x);
  EXPECT_EQ(m.pose.y, predicted.y);
  EXPECT_EQ(m.pose.theta, predicted.theta);
  EXPECT_EQ(m.mean_log_likelihood, 0.0);
}

// A global proposal: a random pose some way off the one the scan was taken
// at climbs to it; with no points it stays; it never goes further than 4x
// its first steps.
TEST_F(LocalMatchTest, AClimbFromAPoseNearTheTruthEndsAtTheTruth) {
  const Pose2 truth{2.0, 3.0, 0.3};
  const ScanPoints points = end_points(w.scan_at(truth), w.map.geometry.resolution);
  const Pose2 mount = w.robot.lidar.mount;
  for (const Pose2& off : {Pose2{0.15, 0.0, 0.0}, Pose2{0.0, -0.12, 0.08}, Pose2{-0.1, 0.1, -0.1}}) {
    const Pose2 climbed = climb_locally(field, points, mount, compose(truth, off), 0.1, 0.05, 90);
    // Within a cell, as the match (the field's levels are quantized).
    EXPECT_NEAR(climbed.x, truth.x, 0.05) << off.x << " " << off.y << " " << off.theta;
    EXPECT_NEAR(climbed.y, truth.y, 0.05) << off.x << " " << off.y << " " << off.theta;
    EXPECT_NEAR(angle_diff(climbed.theta, truth.theta), 0.0, 0.01) << off.x << " " << off.y << " " << off.theta;
  }
  const Pose2 far{3.5, 3.0, 0.3};  // 1.5 m off: the climb's reach is 4 x 0.1 m of the sensor
  const Pose2 from_far = climb_locally(field, points, mount, far, 0.1, 0.05, 90);
  EXPECT_LE(std::hypot(from_far.x - far.x, from_far.y - far.y), 0.4 + 0.15 * 0.2 + 1e-6);
  const Pose2 without = climb_locally(field, {}, mount, far, 0.1, 0.05, 90);
  EXPECT_EQ(without.x, far.x);
  EXPECT_EQ(without.theta, far.theta);
}

// A corridor 4 m wide with fins 1 m deep every 0.6 m along both walls,
// longer than the lidar reaches: a scan in it fits every 0.6 m along it.
SemanticMap finned_corridor() {
  return grid_map(1600, 80, [](int x, int y) {  // 80 m x 4 m
    return y == 0 || y == 79 || ((y < 20 || y >= 60) && x % 12 < 2);
  });
}

// The odometry says the robot went 0.3 m, half the fins' period, while it
// stood: the scan fits 0.3 m behind and 0.3 m ahead of the prediction alike,
// and no better near it. The filter cannot tell which: half the matched
// particles go to each place, and later scans decide (not: none, which left
// fr079 at 60 beams lost where its odometry lost the sign of translation).
TEST(LocalMatchInTheFilter, AScanThatFitsTwoPlacesAboutEquallyPutsParticlesAtBoth) {
  const SemanticMap map = finned_corridor();
  const TrueWorld world(map, WorldOptions{}, "finned corridor");
  const RobotOptions robot =
      load_options<RobotOptions>(std::string(SLAMER_SOURCE_DIR "/config/robots/icart_mini.yaml"));
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 500;
  ParticleFilter filter(map, options, robot.lidar.mount);
  const Pose2 truth{40.25, 2.0, 0.0};
  filter.initialize(truth, {0.02, 0.02, 0.01});
  LaserScan scan = simulated_scan(world, robot, truth);
  for (int k = 0; k < 3; ++k) {  // tracking: the scans fit at the estimate
    scan.utime = 1'000'000 + k * 100'000;
    ASSERT_EQ(filter.update(scan, nullptr).matched, 0);
  }
  filter.predict({0.0, 0.0, 0.0}, {0.3, 0.0, 0.0}, 0.1);
  scan.utime += 100'000;
  const UpdateResult result = filter.update(scan, nullptr);
  EXPECT_EQ(result.matched, 50);
  const auto near = [&](double x) {
    return std::count_if(filter.particles().begin(), filter.particles().end(), [&](const Particle& p) {
      return std::hypot(p.pose.x - x, p.pose.y - truth.y) < 0.15 && std::abs(p.pose.theta) < 0.05;
    });
  };
  // The weights decide how many each place keeps (resampled or not): both
  // keep at least as many as the 25 put there.
  EXPECT_GE(near(truth.x), 25) << near(truth.x) << " at the truth, " << near(truth.x + 0.6) << " a fin further";
  EXPECT_GE(near(truth.x + 0.6), 25) << near(truth.x) << " at the truth, " << near(truth.x + 0.6) << " a fin further";
}

// The small room's doorway (x = 6, y 2.5..3.5), recognized as an open door,
// and the wall beside it as others: the objects a scan from `seen_from` shows.
LineObjectSet door_and_wall_seen_from(const SmallWorld& w, const Pose2& seen_from) {
  const Pose2 sensor = compose(seen_from, w.robot.lidar.mount);
  LineObjectSet set;
  set.class_names = RecognizerOptions{}.classes;
  const auto add = [&](LineKind kind, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& name) {
    LineObject o;
    o.kind = kind;
    o.start = transform_point(inverse(sensor), a);
    o.end = transform_point(inverse(sensor), b);
    o.probs.assign(set.class_names.size(), 0.02f);
    o.probs[static_cast<std::size_t>(std::find(set.class_names.begin(), set.class_names.end(), name) -
                                     set.class_names.begin())] = 0.86f;
    set.objects.push_back(o);
  };
  add(LineKind::kSpatial, {6.0, 2.5}, {6.0, 3.5}, "open_door");
  add(LineKind::kPhysical, {6.0, 3.6}, {6.0, 5.0}, "others");
  add(LineKind::kPhysical, {6.0, 1.0}, {6.0, 2.4}, "others");
  return set;
}

// SLAMER: the odometry says the robot turned 0.2 rad while it stood. The scan
// fits where it stood, and the match goes there when the recognized objects
// agree; when they were seen as from the odometry's pose (as unmapped objects
// along a corridor made a wrong pose fit better on suite world 102006, 0.24 m
// along it: fit 0.66 -> 0.78, the objects 1.4 nats against, the beams 0.4
// for), the objects weigh more against the match than the beams for it (60
// beams), and it is not taken. LFM, which does not weigh objects, takes it.
TEST(LocalMatchInTheFilter, AMatchTheRecognizedObjectsSpeakAgainstIsNotTaken) {
  const SmallWorld w;
  const Pose2 truth{4.0, 3.0, 0.0};
  const Pose2 odometry_says{4.0, 3.0, 0.2};
  LaserScan scan = w.scan_at(truth);
  for (const auto& [mode, objects_agree] :
       {std::pair{LocalizerMode::kSlamer, true}, {LocalizerMode::kSlamer, false}, {LocalizerMode::kLfm, false}}) {
    LocalizerOptions options;
    options.mode = mode;
    options.particles = 500;
    options.lfm.beam_step = 18;  // about 60 beams
    ParticleFilter filter(w.map, options, w.robot.lidar.mount);
    filter.initialize(truth, {0.02, 0.02, 0.01});
    const LineObjectSet at_truth = door_and_wall_seen_from(w, truth);
    for (int k = 0; k < 3; ++k) {  // tracking: the scans fit at the estimate
      scan.utime = 1'000'000 + k * 100'000;
      ASSERT_EQ(filter.update(scan, &at_truth).matched, 0);
    }
    filter.predict({0.0, 0.0, 0.0}, {0.0, 0.0, 0.2}, 0.1);
    scan.utime += 100'000;
    const LineObjectSet objects = objects_agree ? at_truth : door_and_wall_seen_from(w, odometry_says);
    EXPECT_EQ(filter.update(scan, &objects).matched, mode == LocalizerMode::kLfm || objects_agree ? 50 : 0)
        << (mode == LocalizerMode::kLfm ? "lfm" : "slamer") << (objects_agree ? ", objects agree" : "");
  }
}

TEST(LocalMatchOptions, AreReadAndBadValuesRefusedWithTheirKey) {
  const auto error_of = localizer_options_error;
  const auto o = parse_options<LocalizerOptions>("recovery: {local: {below: 0, shift: 1.0, turn: 0.3}}\n", "l.yaml");
  EXPECT_EQ(o.recovery.local.below, 0.0);  // off
  EXPECT_EQ(o.recovery.local.shift, 1.0);
  EXPECT_EQ(o.recovery.local.turn, 0.3);
  EXPECT_EQ(o.recovery.local.fraction, LocalMatchOptions{}.fraction);
  EXPECT_NE(error_of("recovery: {local: {fraction: 1.5}}\n").find("'recovery.local.fraction'"), std::string::npos);
  EXPECT_NE(error_of("recovery: {local: {turn: -0.1}}\n").find("'recovery.local.turn'"), std::string::npos);
  EXPECT_NE(error_of("recovery: {local: {window: 1}}\n").find("recovery.local.window"), std::string::npos)
      << error_of("recovery: {local: {window: 1}}\n");
}

}  // namespace
}  // namespace slamer

// Along-track evidence (localizer/along_track.hpp) and the status rule on it:
// in a corridor whose walls fit from anywhere along it, a few posts say where
// along it the robot is; an estimate 0.6 m off along the heading still fits
// the walls, and the scans keep preferring the pose 0.6 m back.
#include <gtest/gtest.h>

#include <cmath>

#include "localizer/along_track.hpp"
#include "localizer/localizer_options.hpp"
#include "localizer/particle_filter.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

constexpr const char* kNotPinned = "no scan has pinned the position along the heading since it was last in doubt";

// 30 m x 3 m, posts 10 cm wide and 30 cm deep on the lower wall every 2 m
// and on the upper every 3.5 m (together: every 14 m the same).
SemanticMap posted_corridor() {
  return grid_map(600, 60, [](int x, int y) {
    return y == 0 || y == 59 || (y < 7 && x % 40 < 2) || (y >= 53 && (x + 13) % 70 < 2);
  });
}

class AlongTrackTest : public ::testing::Test {
 protected:
  SemanticMap map = posted_corridor();
  TrueWorld world{map, WorldOptions{}, "posted corridor"};
  RobotOptions robot = load_options<RobotOptions>(std::string(SLAMER_SOURCE_DIR "/config/robots/icart_mini.yaml"));
  const Pose2 truth{15.1, 1.5, 0.0};
  LaserScan scan = simulated_scan(world, robot, truth);
};

TEST_F(AlongTrackTest, PrefersThePoseTheScanWasTakenAtAlongTheHeading) {
  const LikelihoodField field(std::make_shared<const DistanceField>(obstacle_distance_field(map, 1.2)), {});
  const ScanPoints points = end_points(scan, map.geometry.resolution);
  for (const double off : {0.6, -0.6}) {
    const Pose2 ahead{truth.x + off, truth.y, truth.theta};
    const AlongTrackPreference p = along_track_preference(field, points, robot.lidar.mount, ahead, {});
    EXPECT_NEAR(p.shift, -off, 1e-9) << off;
    EXPECT_GT(p.gain, StatusOptions{}.along_track_gain) << off;
    EXPECT_DOUBLE_EQ(p.margin, -p.gain) << off;
  }
  // At the truth nothing along the heading scores better, every shift clearly worse; with no points
  // there is nothing to prefer.
  const AlongTrackPreference at_truth = along_track_preference(field, points, robot.lidar.mount, truth, {});
  EXPECT_EQ(at_truth.shift, 0.0);
  EXPECT_EQ(at_truth.gain, 0.0);
  EXPECT_GT(at_truth.margin, StatusOptions{}.along_track_gain) << "the posts pin the truth";
  const AlongTrackPreference none = along_track_preference(field, {}, robot.lidar.mount, truth, {});
  EXPECT_EQ(none.shift, 0.0);
  EXPECT_EQ(none.gain, 0.0);
}

// A cloud held 0.6 m ahead (tight, the local match off, the robot standing):
// the walls fit, so the fit rules say OK; no scan pins a pose given by hand
// that is off, so the status says UNCERTAIN from the first scans, and after
// along_track_time of scans that prefer the pose behind it (and 10 of them)
// it says that. The poses are the same with the rules off.
TEST_F(AlongTrackTest, AnEstimateTheScansKeepPlacingElsewhereAlongTheHeadingIsUncertain) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  options.recovery.local.below = 0.0;
  std::vector<UpdateResult> runs[2];
  for (const double gain : {StatusOptions{}.along_track_gain, 0.0}) {
    options.status.along_track_gain = gain;
    ParticleFilter filter(map, options, robot.lidar.mount);
    filter.initialize({truth.x + 0.6, truth.y, truth.theta}, {0.01, 0.01, 0.002});
    for (int k = 0; k < 40; ++k) {  // 4 s at 10 Hz
      scan.utime = 1'000'000 + k * 100'000;
      runs[gain > 0.0 ? 0 : 1].push_back(filter.update(scan, nullptr));
    }
  }
  for (std::size_t k = 0; k < runs[0].size(); ++k) {
    const PoseEstimate& with = runs[0][k].estimate;
    const PoseEstimate& without = runs[1][k].estimate;
    EXPECT_EQ(with.pose.x, without.pose.x) << k;
    EXPECT_GT(with.pose.x - truth.x, 0.4) << "the cloud stays ahead, scan " << k;
    EXPECT_GT(runs[0][k].fit, 0.75) << "the walls fit, scan " << k;
    if (k >= 5) {  // once the first scans' spread has settled
      EXPECT_EQ(without.status, LocalizerStatus::kOk) << k << ": " << without.status_reason;
    }
    if (k >= 20) {  // 2 s after the first scan (and more than 10 scans)
      EXPECT_EQ(with.status, LocalizerStatus::kUncertain) << k;
      EXPECT_STREQ(with.status_reason, "the scans have fitted a pose along the heading better for a while") << k;
    } else if (k >= 5) {
      EXPECT_STREQ(with.status_reason, kNotPinned) << k;
    }
  }
}

// A scan every 0.5 s (a slow log): 2 s is 5 scans, too few; the 10th says so.
TEST_F(AlongTrackTest, ASlowLogNeedsAlongTrackScansOfEvidenceNotOnlyTheTime) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  options.recovery.local.below = 0.0;
  ParticleFilter filter(map, options, robot.lidar.mount);
  filter.initialize({truth.x + 0.6, truth.y, truth.theta}, {0.01, 0.01, 0.002});
  for (int k = 0; k < 14; ++k) {
    scan.utime = 1'000'000 + k * 500'000;
    const PoseEstimate e = filter.update(scan, nullptr).estimate;
    if (k >= 9) {
      EXPECT_STREQ(e.status_reason, "the scans have fitted a pose along the heading better for a while") << k;
    } else if (k >= 5) {
      EXPECT_STREQ(e.status_reason, kNotPinned) << k;
    }
  }
}

// A pose given by hand where the scans cannot say where along the corridor
// the robot is (plain walls, both ends out of range) is UNCERTAIN however well
// the walls fit; given where posts are in view, the first scans pin it: OK.
TEST_F(AlongTrackTest, APoseGivenInAPlainCorridorIsUncertainOneAmongPostsIsOk) {
  // 80 m x 3 m, open at both ends; posts every 2 m in the last 20 m only.
  const SemanticMap plain =
      grid_map(1600, 60, [](int x, int y) { return y == 0 || y == 59 || (x >= 1200 && y < 7 && x % 40 < 2); });
  const TrueWorld plain_world{plain, WorldOptions{}, "corridor posted at one end"};
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  ParticleFilter filter(plain, options, robot.lidar.mount);
  for (const Pose2 given : {Pose2{20.1, 1.5, 0.0}, Pose2{70.1, 1.5, 0.0}}) {
    filter.initialize(given, {0.01, 0.01, 0.002});
    LaserScan given_scan = simulated_scan(plain_world, robot, given);
    for (int k = 0; k < 20; ++k) {
      given_scan.utime = (given.x > 50.0 ? 10'000'000 : 1'000'000) + k * 100'000;
      const UpdateResult r = filter.update(given_scan, nullptr);
      EXPECT_LT(std::abs(r.estimate.pose.x - given.x), 0.1) << given.x << " " << k;
      if (k < 5) {
        continue;  // the first scans' spread settles
      }
      EXPECT_GT(r.fit, 0.75) << "the walls fit, " << given.x << " " << k;
      if (given.x < 50.0) {
        EXPECT_STREQ(r.estimate.status_reason, kNotPinned) << k;
      } else {
        EXPECT_EQ(r.estimate.status, LocalizerStatus::kOk) << k << ": " << r.estimate.status_reason;
      }
    }
  }
  // The rule off (status.along_track_pin): the plain corridor's pose says OK.
  options.status.along_track_pin = false;
  ParticleFilter unpinned(plain, options, robot.lidar.mount);
  unpinned.initialize({20.1, 1.5, 0.0}, {0.01, 0.01, 0.002});
  LaserScan plain_scan = simulated_scan(plain_world, robot, {20.1, 1.5, 0.0});
  for (int k = 0; k < 20; ++k) {
    plain_scan.utime = 1'000'000 + k * 100'000;
    const PoseEstimate e = unpinned.update(plain_scan, nullptr).estimate;
    if (k >= 5) {
      EXPECT_EQ(e.status, LocalizerStatus::kOk) << k << ": " << e.status_reason;
    }
  }
}

}  // namespace
}  // namespace slamer

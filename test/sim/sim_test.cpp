#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tools/sim/simulator.hpp"
#include "tools/sim/world.hpp"

namespace slamer {
namespace {

constexpr double kPi = std::numbers::pi;

// A 20 m x 10 m map at 0.1 m with classes door, glass_door, fence,
// no_entry_line, others; cells are painted per test.
SemanticMap make_map(double yaw = 0.0) {
  SemanticMap map;
  map.geometry = {200, 100, 0.1, {0.0, 0.0, yaw}};
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  map.classes = {{"door", {255, 0, 255}},
                 {"glass_door", {0, 255, 255}},
                 {"fence", {255, 128, 0}},
                 {"no_entry_line", {255, 0, 0}},
                 {"others", {0, 0, 0}}};
  return map;
}

// Paints cells x in [x0, x1], y in [y0, y1] with a class (or a plain wall for -1).
void paint(SemanticMap* map, int x0, int x1, int y0, int y1, int label, bool occupied = true) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      map->labels[map->geometry.index(x, y)] = static_cast<int8_t>(label);
      map->occupancy[map->geometry.index(x, y)] = occupied ? Occupancy::kOccupied : Occupancy::kFree;
    }
  }
}

double hit_fraction(const TrueWorld& world, const Eigen::Vector2d& origin, double angle, double time, int n) {
  std::mt19937 rng(5);
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    hits += std::isfinite(world.cast(origin, angle, 30.0, time, rng)) ? 1 : 0;
  }
  return static_cast<double>(hits) / n;
}

TEST(RayCast, HandComputedDistances) {
  SemanticMap map = make_map();
  paint(&map, 150, 150, 0, 99, -1);  // wall whose near face is at x = 15.0
  paint(&map, 0, 149, 80, 80, -1);   // wall whose near face is at y = 8.0
  const TrueWorld world(map, WorldOptions{}, "test");
  std::mt19937 rng(1);
  EXPECT_NEAR(world.cast({2.05, 5.05}, 0.0, 30.0, 0.0, rng), 12.95, 1e-9);
  // 45 degrees from (2, 5): y = 8 is reached after 3 / sin(45) = 4.2426 m.
  EXPECT_NEAR(world.cast({2.0, 5.0}, kPi / 4, 30.0, 0.0, rng), 3.0 * std::sqrt(2.0), 1e-9);
  // 15 degrees below the x axis to x = 15: 13 / cos(15).
  EXPECT_NEAR(world.cast({2.0, 5.0}, -kPi / 12, 30.0, 0.0, rng), 13.0 / std::cos(kPi / 12), 1e-9);
  // 30 degrees below leaves the map (y < 0) before x = 15.
  EXPECT_TRUE(std::isinf(world.cast({2.0, 5.0}, -kPi / 6, 30.0, 0.0, rng)));
  // Beyond max range: nothing returns.
  EXPECT_TRUE(std::isinf(world.cast({2.05, 5.05}, 0.0, 10.0, 0.0, rng)));
  // Off the map: nothing returns.
  EXPECT_TRUE(std::isinf(world.cast({2.05, 5.05}, kPi, 30.0, 0.0, rng)));
  // Starting inside a wall: range 0.
  EXPECT_NEAR(world.cast({15.05, 5.05}, 0.0, 30.0, 0.0, rng), 0.0, 1e-12);
}

TEST(RayCast, RotatedMapOrigin) {
  SemanticMap map = make_map(kPi / 2);  // grid x points along world +y
  paint(&map, 150, 150, 0, 99, -1);     // the wall is at world y = 15
  const TrueWorld world(map, WorldOptions{}, "test");
  std::mt19937 rng(1);
  // Grid cell (20, 50) centre is at world (-5.05, 2.05).
  EXPECT_NEAR(world.cast({-5.05, 2.05}, kPi / 2, 30.0, 0.0, rng), 12.95, 1e-9);
}

TEST(RayCast, PartialReturnsAreDrawnOncePerObject) {
  SemanticMap map = make_map();
  paint(&map, 100, 102, 0, 99, 1);         // a glass door 3 cells thick
  paint(&map, 120, 123, 0, 99, 2);         // a fence 4 cells thick
  paint(&map, 160, 160, 0, 99, 3, false);  // a no-entry line: never returns
  paint(&map, 180, 180, 0, 99, 4);         // a wall behind everything
  WorldOptions options;
  const TrueWorld world(map, options, "test");
  // Glass alone returns 30 % of beams whatever its thickness.
  EXPECT_NEAR(hit_fraction(world, {5.0, 5.05}, 0.0, 0.0, 20000), 1.0, 1e-12);  // the wall is behind
  std::mt19937 rng(9);
  int glass = 0;
  int fence = 0;
  int wall = 0;
  for (int i = 0; i < 20000; ++i) {
    const double r = world.cast({5.0, 5.05}, 0.0, 30.0, 0.0, rng);
    glass += std::abs(r - 5.0) < 1e-6 ? 1 : 0;
    fence += std::abs(r - 7.0) < 1e-6 ? 1 : 0;
    wall += std::abs(r - 13.0) < 1e-6 ? 1 : 0;
  }
  EXPECT_NEAR(glass / 20000.0, 0.3, 0.015);
  EXPECT_NEAR(fence / 20000.0, 0.7 * 0.4, 0.015);
  EXPECT_NEAR(wall / 20000.0, 0.7 * 0.6, 0.015);
  EXPECT_EQ(glass + fence + wall, 20000);  // nothing stops at the no-entry line
}

TEST(RayCast, DoorsFollowTheirSchedule) {
  SemanticMap map = make_map();
  paint(&map, 100, 100, 40, 59, 0);  // a door drawn closed in the map
  paint(&map, 150, 150, 0, 99, -1);  // wall behind it
  WorldOptions options;
  DoorTruth truth;
  truth.near = {10.05, 5.0};
  truth.changes = {{10.0, DoorState::kOpen}, {20.0, DoorState::kClosed}};
  options.doors = {truth};
  const TrueWorld world(map, options, "test");
  ASSERT_EQ(world.door_count(), 1);
  std::mt19937 rng(1);
  EXPECT_NEAR(world.cast({5.0, 5.05}, 0.0, 30.0, 0.0, rng), 5.0, 1e-9);    // closed, as mapped
  EXPECT_NEAR(world.cast({5.0, 5.05}, 0.0, 30.0, 15.0, rng), 10.0, 1e-9);  // opened at 10 s
  EXPECT_NEAR(world.cast({5.0, 5.05}, 0.0, 30.0, 25.0, rng), 5.0, 1e-9);   // closed again at 20 s
  EXPECT_EQ(world.door_state(0, 12.0), DoorState::kOpen);
  EXPECT_EQ(world.door_at({10.05, 5.0}), 0);
  EXPECT_EQ(world.door_at({11.0, 5.0}), -1);
}

TEST(RayCast, TruthObjectsBlockBeamsAndHaveAClass) {
  SemanticMap map = make_map();
  WorldOptions options;
  options.objects.push_back({"others", {8.0, 3.0}, {8.0, 7.0}, 0.2});
  const TrueWorld world(map, options, "test");
  std::mt19937 rng(1);
  EXPECT_NEAR(world.cast({5.0, 5.05}, 0.0, 30.0, 0.0, rng), 2.9, 0.051);
  EXPECT_EQ(world.class_near({8.0, 5.0}, 0.2), map.class_index("others"));
  EXPECT_EQ(world.class_near({12.0, 5.0}, 0.2), -1);
}

TEST(TrueWorld, ErrorsNameTheWorldFile) {
  SemanticMap map = make_map();
  WorldOptions options;
  options.doors.push_back({{3.0, 3.0}, DoorState::kOpen, {}});
  try {
    TrueWorld(map, options, "w.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "w.yaml: truth.doors[0]: no door within 0.500000 m of (3.000000, 3.000000)");
  }
  options.doors.clear();
  options.objects.push_back({"piano", {1.0, 1.0}, {2.0, 1.0}, 0.1});
  try {
    TrueWorld(map, options, "w.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "w.yaml: truth.objects[0]: class 'piano' is not in the map's class table");
  }
}

class RecordingSink : public SimulatorSink {
 public:
  void on_scan(const LaserScan& scan, int64_t publish_utime) override {
    scans.push_back(scan);
    publish_times.push_back(publish_utime);
  }
  void on_encoders(const EncoderSample& s) override { encoders.push_back(s); }
  void on_odometry(const OdometrySample& s) override { odometry.push_back(s); }
  void on_ground_truth(const GroundTruthSample& s) override { truth.push_back(s); }
  std::vector<LaserScan> scans;
  std::vector<int64_t> publish_times;
  std::vector<EncoderSample> encoders;
  std::vector<OdometrySample> odometry;
  std::vector<GroundTruthSample> truth;
};

// An empty room 18 m x 8 m with walls around, for driving tests.
SemanticMap make_room() {
  SemanticMap map = make_map();
  paint(&map, 10, 190, 10, 10, -1);
  paint(&map, 10, 190, 90, 90, -1);
  paint(&map, 10, 10, 10, 90, -1);
  paint(&map, 190, 190, 10, 90, -1);
  return map;
}

RecordingSink run(const TrueWorld& world, const WorldOptions& options, SimOptions sim_options, uint64_t seed) {
  RobotOptions robot;
  Simulator sim(world, options, robot, sim_options, seed);
  RecordingSink sink;
  while (sim.step(sink)) {
  }
  return sink;
}

WorldOptions square_path() {
  WorldOptions options;
  options.start = {3.0, 3.0, 0.0};
  options.path = {{PathStep::Kind::kGoTo, {15.0, 3.0}, 0.8, 0, 0},
                  {PathStep::Kind::kGoTo, {15.0, 7.0}, 0.8, 0, 0},
                  {PathStep::Kind::kTurnTo, {}, 0, kPi, 0},
                  {PathStep::Kind::kWait, {}, 0, 0, 1.0},
                  {PathStep::Kind::kGoTo, {3.0, 3.0}, 0.8, 0, 0}};
  return options;
}

TEST(Simulator, FollowsThePathAndReportsAtTheConfiguredRates) {
  const SemanticMap map = make_room();
  const WorldOptions options = square_path();
  const TrueWorld world(map, options, "test");
  const RecordingSink sink = run(world, options, SimOptions{}, 7);
  ASSERT_FALSE(sink.truth.empty());
  const Pose2 end = sink.truth.back().pose;
  EXPECT_NEAR(end.x, 3.0, 0.06);
  EXPECT_NEAR(end.y, 3.0, 0.06);
  // 40 Hz scans, 100 Hz encoders, ground truth for every scan at the scan's utime.
  ASSERT_GT(sink.scans.size(), 100u);
  EXPECT_EQ(sink.scans[1].utime - sink.scans[0].utime, 25'000);
  EXPECT_EQ(sink.encoders[1].utime - sink.encoders[0].utime, 10'000);
  EXPECT_EQ(sink.truth.size(), sink.scans.size());
  for (std::size_t i = 0; i < sink.scans.size(); ++i) {
    ASSERT_EQ(sink.truth[i].utime, sink.scans[i].utime);
    ASSERT_EQ(sink.scans[i].seq, static_cast<int64_t>(i));
    ASSERT_GT(sink.publish_times[i], sink.scans[i].utime);
  }
  EXPECT_EQ(sink.scans[0].ranges.size(), 1081u);
  EXPECT_NEAR(sink.scans[0].angle_increment, 0.25 * kPi / 180.0, 1e-9);
  // Dead reckoning is close but not exact (wrong wheel radii, slip).
  const Pose2 odom_end = sink.odometry.back().pose;
  const double odom_error = std::hypot(odom_end.x, odom_end.y);
  EXPECT_GT(odom_error, 1e-3);
  EXPECT_LT(odom_error, 1.0);
}

TEST(Simulator, ScansSeeTheWallsWhereTheyAre) {
  const SemanticMap map = make_room();
  WorldOptions options;
  options.start = {5.0, 5.0, 0.0};
  options.path = {{PathStep::Kind::kWait, {}, 0, 0, 0.2}};
  const TrueWorld world(map, options, "test");
  SimOptions sim_options;
  sim_options.range_stddev = 0.0;
  sim_options.dropout_probability = 0.0;
  const RecordingSink sink = run(world, options, sim_options, 1);
  ASSERT_FALSE(sink.scans.empty());
  const LaserScan& scan = sink.scans.front();
  // RobotOptions{} mounts the LiDAR on the base origin (5, 5); the east wall's face is at x = 19.0.
  EXPECT_NEAR(scan.ranges[540], 19.0 - 5.0, 1e-6);
  // Straight left (+90 deg, beam 900): the north wall's face is at y = 9.0.
  EXPECT_NEAR(scan.ranges[900], 4.0, 1e-6);
  // Behind-left (+135 deg, beam 1080) reaches the west wall (x = 1.1) or north wall.
  EXPECT_TRUE(std::isfinite(scan.ranges[1080]));
}

TEST(Simulator, SameSeedSameRunOtherSeedOtherNoise) {
  const SemanticMap map = make_room();
  const WorldOptions options = square_path();
  const TrueWorld world(map, options, "test");
  const RecordingSink a = run(world, options, SimOptions{}, 42);
  const RecordingSink b = run(world, options, SimOptions{}, 42);
  const RecordingSink c = run(world, options, SimOptions{}, 43);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  for (std::size_t i = 0; i < a.scans.size(); i += 97) {
    for (std::size_t j = 0; j < a.scans[i].ranges.size(); ++j) {
      const float x = a.scans[i].ranges[j];
      const float y = b.scans[i].ranges[j];
      ASSERT_TRUE(x == y || (std::isnan(x) && std::isnan(y)));
    }
  }
  EXPECT_EQ(a.encoders.back().left, b.encoders.back().left);
  EXPECT_NE(a.encoders.back().left, c.encoders.back().left);
  EXPECT_NE(a.scans[10].ranges, c.scans[10].ranges);
}

TEST(Simulator, MotionDistortionShiftsLateBeams) {
  const SemanticMap map = make_room();
  WorldOptions options;
  options.start = {9.0, 5.0, 0.0};
  options.path = {{PathStep::Kind::kTurnTo, {}, 0, kPi / 2, 0}};  // spin at up to 3.14 rad/s
  const TrueWorld world(map, options, "test");
  SimOptions distorted;
  distorted.range_stddev = 0.0;
  distorted.dropout_probability = 0.0;
  SimOptions rigid = distorted;
  rigid.motion_distortion = false;
  const RecordingSink a = run(world, options, distorted, 1);
  const RecordingSink b = run(world, options, rigid, 1);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  // While turning, the first beam is cast from the same pose either way; the last is not.
  const std::size_t mid = a.scans.size() / 2;
  EXPECT_FLOAT_EQ(a.scans[mid].ranges[0], b.scans[mid].ranges[0]);
  EXPECT_NE(a.scans[mid].ranges[1080], b.scans[mid].ranges[1080]);
}

}  // namespace
}  // namespace slamer

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

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

// Odometry error model (issue 9): dead-reckoning heading drift of the odometry against the truth.
struct Drift {
  double path = 0.0;           // [m] true path length
  double heading_error = 0.0;  // [rad] odometry heading change minus the true one, over the run
  double odometry_turn = 0.0;  // [rad] summed |heading change| of odometry and truth
  double true_turn = 0.0;
  std::vector<double> jumps;  // per scan interval: change of the heading error [rad]
};

Drift drift_of(const RecordingSink& sink) {
  Drift d;
  std::size_t k = 0;
  std::optional<double> previous_error;
  for (std::size_t i = 0; i < sink.truth.size(); ++i) {
    while (k + 1 < sink.odometry.size() && sink.odometry[k + 1].utime <= sink.truth[i].utime) {
      ++k;
    }
    // The odometry at the scan's time (100 Hz samples, interpolated).
    double odometry_theta = sink.odometry[k].pose.theta;
    if (k + 1 < sink.odometry.size() && sink.odometry[k].utime <= sink.truth[i].utime) {
      const double f = static_cast<double>(sink.truth[i].utime - sink.odometry[k].utime) /
                       static_cast<double>(sink.odometry[k + 1].utime - sink.odometry[k].utime);
      odometry_theta += f * angle_diff(sink.odometry[k + 1].pose.theta, odometry_theta);
    }
    const double error = angle_diff(angle_diff(odometry_theta, sink.odometry.front().pose.theta),
                                    angle_diff(sink.truth[i].pose.theta, sink.truth.front().pose.theta));
    if (i > 0) {
      const Pose2& a = sink.truth[i - 1].pose;
      const Pose2& b = sink.truth[i].pose;
      d.path += std::hypot(b.x - a.x, b.y - a.y);
      d.true_turn += std::abs(angle_diff(b.theta, a.theta));
      d.jumps.push_back(angle_diff(error, *previous_error));
    }
    previous_error = error;
    d.heading_error = error;
  }
  for (std::size_t i = 1; i < sink.odometry.size(); ++i) {
    d.odometry_turn += std::abs(angle_diff(sink.odometry[i].pose.theta, sink.odometry[i - 1].pose.theta));
  }
  return d;
}

// The odometry tests need the truth at scan times, not the scans: 3 beams keep them fast.
RecordingSink run_odometry(const TrueWorld& world, const WorldOptions& options, SimOptions sim_options, uint64_t seed) {
  RobotOptions robot;
  robot.lidar.beams = 3;
  Simulator sim(world, options, robot, sim_options, seed);
  RecordingSink sink;
  while (sim.step(sink)) {
  }
  return sink;
}

SimOptions exact_odometry() {
  SimOptions o;
  o.wheel_radius_error_left = o.wheel_radius_error_right = o.tread_error = o.slip_stddev = 0.0;
  o.range_stddev = 0.0;
  return o;
}

TEST(OdometryErrors, RadiusErrorsOfOnePercentDriftAsRealRobotsDo) {
  const TrueWorld world(make_room(), square_path(), "room");
  const RecordingSink exact = run_odometry(world, square_path(), exact_odometry(), 1);
  EXPECT_LT(std::abs(drift_of(exact).heading_error), 0.002);  // only tick quantization
  // +-1 % radius (left +1 %, right -1 %): straight driving turns the odometry by
  // 2 * 0.01 / tread rad per metre (3.73 deg/m for the i-Cart mini's 0.307 m tread).
  SimOptions uncalibrated = exact_odometry();
  uncalibrated.wheel_radius_error_left = 0.01;
  uncalibrated.wheel_radius_error_right = -0.01;
  const Drift d = drift_of(run_odometry(world, square_path(), uncalibrated, 1));
  RobotOptions robot;
  const double expected = 0.02 / robot.base.tread;  // [rad/m]
  EXPECT_GT(d.path, 25.0);
  EXPECT_NEAR(std::abs(d.heading_error) / d.path, expected, 0.05 * expected);
  EXPECT_GT(std::abs(d.heading_error) / d.path * 180.0 / kPi, 3.0);  // 3-5 deg/m
  EXPECT_LT(std::abs(d.heading_error) / d.path * 180.0 / kPi, 5.0);
}

TEST(OdometryErrors, TurnSlipGrowsWithTheYawRate) {
  const TrueWorld world(make_room(), square_path(), "room");
  SimOptions slipping = exact_odometry();
  slipping.wheel_slip.turn_slip = 0.1;  // 10 % more differential travel per rad/s
  const Drift exact = drift_of(run_odometry(world, square_path(), exact_odometry(), 1));
  const Drift d = drift_of(run_odometry(world, square_path(), slipping, 1));
  EXPECT_NEAR(exact.odometry_turn / exact.true_turn, 1.0, 0.03);  // sampling and ticks
  // The odometry overstates the turns by turn_slip x |yaw rate| (about 0.5-1 rad/s on this path).
  const double excess = (d.odometry_turn / d.true_turn) / (exact.odometry_turn / exact.true_turn) - 1.0;
  EXPECT_GT(excess, 0.1 * 0.4);
  EXPECT_LT(excess, 0.1 * 1.5);
  // The random part: the same seed gives the same run, another seed another drift.
  SimOptions noisy = exact_odometry();
  noisy.wheel_slip.turn_slip_stddev = 0.1;
  const Drift a = drift_of(run_odometry(world, square_path(), noisy, 5));
  const Drift b = drift_of(run_odometry(world, square_path(), noisy, 5));
  const Drift c = drift_of(run_odometry(world, square_path(), noisy, 6));
  EXPECT_EQ(a.heading_error, b.heading_error);
  EXPECT_NE(a.heading_error, c.heading_error);
  EXPECT_GT(std::abs(a.heading_error - exact.heading_error), 1e-3);
}

TEST(OdometryErrors, BumpsAreShortSpikesOfOneWheel) {
  const TrueWorld world(make_room(), square_path(), "room");
  SimOptions bumpy = exact_odometry();
  bumpy.wheel_slip.bump_rate = 0.5;  // [1/s]
  bumpy.wheel_slip.bump_travel = 0.02;
  bumpy.wheel_slip.bump_duration = 0.05;
  const RecordingSink sink = run_odometry(world, square_path(), bumpy, 3);
  const Drift d = drift_of(sink);
  const Drift exact = drift_of(run_odometry(world, square_path(), exact_odometry(), 3));
  ASSERT_EQ(d.jumps.size(), exact.jumps.size());  // the robot drives the same (the true pose steers it)
  // A bump turns the odometry by bump_travel / tread within bump_duration: find
  // the runs of scan intervals where the heading error moves, and their sizes.
  RobotOptions robot;
  const double kick = 0.02 / robot.base.tread;
  std::vector<double> bumps;
  double current = 0.0;
  for (std::size_t i = 0; i < d.jumps.size(); ++i) {
    const double jump = d.jumps[i] - exact.jumps[i];
    if (std::abs(jump) > 0.05 * kick) {
      current += jump;
    } else if (current != 0.0) {
      bumps.push_back(current);
      current = 0.0;
    }
  }
  const double seconds = static_cast<double>(sink.truth.back().utime - sink.truth.front().utime) * 1e-6;
  const double expected = 0.5 * seconds;
  EXPECT_GT(static_cast<double>(bumps.size()), expected - 3.0 * std::sqrt(expected));
  EXPECT_LT(static_cast<double>(bumps.size()), expected + 3.0 * std::sqrt(expected));
  for (const double b : bumps) {
    EXPECT_NEAR(std::abs(b), kick, 0.15 * kick);
  }
}

}  // namespace
}  // namespace slamer

// The world generator: every world of seeds 1..20 is valid (closed rooms, a
// route clear of every closed object, the differences recorded), the same seed
// gives the same bytes, the check finds broken worlds, and the simulator's
// additions (removed objects, intensities) behave.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "test/support/child_process.hpp"
#include "tools/sim/floor_plan.hpp"
#include "tools/sim/simulator.hpp"
#include "tools/worldgen/world_check.hpp"
#include "tools/worldgen/world_files.hpp"

namespace slamer {
namespace {

const std::string kRobot = std::string(SLAMER_SOURCE_DIR "/config/robots/icart_mini.yaml");

std::string make_world(uint64_t seed, const std::string& name, const WorldGenOptions& options = {}) {
  const std::string dir = std::string(SLAMER_BINARY_DIR "/worldgen_test/") + name;
  std::filesystem::remove_all(dir);
  write_world(generate_building(options, seed), options, seed, kRobot, dir);
  return dir;
}

TEST(WorldGen, EveryWorldOfSeeds1To20IsValid) {
  int turned = 0, differing_doors = 0, changing_doors = 0, framed = 0, flush = 0, glass = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const std::string dir = make_world(seed, "seed" + std::to_string(seed));
    const WorldCheckResult check = check_world(dir + "/world.yaml");
    EXPECT_TRUE(check.problems.empty()) << "seed " << seed << ": " << check.problems.front();
    EXPECT_GT(check.route_length, 10.0) << "seed " << seed;
    EXPECT_GT(check.reachable_cells, 10000u) << "seed " << seed;
    const auto world = load_options<WorldOptions>(dir + "/world.yaml");
    const auto differences = load_options<MapDifferences>(dir + "/differences.yaml");
    EXPECT_EQ(differences.seed, static_cast<int64_t>(seed));
    EXPECT_EQ(differences.doors.size(), world.doors.size()) << "seed " << seed;
    EXPECT_EQ(differences.added, static_cast<int>(world.objects.size()));
    EXPECT_EQ(differences.removed, static_cast<int>(world.removed.size()));
    EXPECT_GE(differences.added, 1) << "seed " << seed << ": the truth has no object the map lacks";
    for (std::size_t i = 0; i < world.doors.size(); ++i) {
      const MapDifferences::Door& door = differences.doors[i];
      EXPECT_GE(door.width, 0.7 - 1e-6);
      EXPECT_LE(door.width, 1.8 + 1e-6);
      EXPECT_EQ(door.truth_state, *world.doors[i].state == DoorState::kOpen ? "open" : "closed");
      EXPECT_EQ(door.changes.size(), world.doors[i].changes.size());
      if (door.on_route) {
        EXPECT_EQ(door.truth_state, "open");
        EXPECT_TRUE(door.changes.empty());
      }
      differing_doors += door.differs() ? 1 : 0;
      changing_doors += door.changes.empty() ? 0 : 1;
      framed += door.framed ? 1 : 0;
      flush += door.framed ? 0 : 1;
      glass += door.class_name == "glass_door" ? 1 : 0;
    }
    const double heading = std::fmod(std::abs(world.start.theta), M_PI / 2);
    turned += heading > 0.05 && heading < M_PI / 2 - 0.05 ? 1 : 0;
    EXPECT_EQ(world.reflectance.size(), 5u);
  }
  EXPECT_GE(turned, 8) << "too few buildings at an angle";
  EXPECT_GE(differing_doors, 40);
  EXPECT_GE(changing_doors, 10);
  EXPECT_GE(framed, 40);
  EXPECT_GE(flush, 40);
  EXPECT_GE(glass, 20);
}

TEST(WorldGen, SameSeedSameBytesOtherSeedOthers) {
  const std::string a = make_world(7, "same_a");
  const std::string b = make_world(7, "same_b");
  const std::string c = make_world(8, "same_c");
  for (const std::string file :
       {"plan.yaml", "map.pgm", "semantic.png", "map.yaml", "world.yaml", "differences.yaml"}) {
    const std::string bytes = test::read_file(a + "/" + file);
    EXPECT_FALSE(bytes.empty()) << file;
    EXPECT_TRUE(bytes == test::read_file(b + "/" + file)) << file << " differs for the same seed";
  }
  EXPECT_FALSE(test::read_file(a + "/world.yaml") == test::read_file(c + "/world.yaml"));
  EXPECT_FALSE(test::read_file(a + "/semantic.png") == test::read_file(c + "/semantic.png"));
}

TEST(WorldGen, TheCheckFindsAClosedDoorOnTheRouteAndALeak) {
  const std::string dir = make_world(3, "broken");
  ASSERT_TRUE(check_world(dir + "/world.yaml").problems.empty());
  // The first door on the route shut in the truth.
  const auto differences = load_options<MapDifferences>(dir + "/differences.yaml");
  std::size_t on_route = 0;
  while (on_route < differences.doors.size() && !differences.doors[on_route].on_route) {
    ++on_route;
  }
  ASSERT_LT(on_route, differences.doors.size());
  std::string text = test::read_file(dir + "/world.yaml");
  std::size_t at = text.find("  doors:\n");
  for (std::size_t i = 0; i <= on_route; ++i) {
    at = text.find("state: ", at + 1);
  }
  text.replace(at, std::string("state: open").size(), "state: closed");
  std::ofstream(dir + "/shut.yaml") << text;
  const WorldCheckResult shut = check_world(dir + "/shut.yaml");
  ASSERT_FALSE(shut.problems.empty());
  EXPECT_NE(shut.problems[0].find("door (not open throughout)"), std::string::npos) << shut.problems[0];
  // Walls gone: the route's region reaches the unknown outside.
  auto plan = load_options<FloorPlan>(dir + "/plan.yaml");
  std::erase_if(plan.shapes, [](const PlanShape& s) { return s.class_name == "others" && s.width > 0.12; });
  write_floor_plan_map(plan, dir);
  const WorldCheckResult leak = check_world(dir + "/world.yaml");
  ASSERT_FALSE(leak.problems.empty());
  EXPECT_NE(leak.problems[0].find("open to the outside"), std::string::npos) << leak.problems[0];
}

TEST(WorldGen, RemovedObjectsAreGoneFromTheTruthOnly) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const std::string dir = make_world(seed, "removed" + std::to_string(seed));
    const auto world = load_options<WorldOptions>(dir + "/world.yaml");
    if (world.removed.empty()) {
      continue;
    }
    const SemanticMap map = load_semantic_map(world.map_path);
    const TrueWorld truth(map, world, dir);
    WorldOptions as_mapped = world;
    as_mapped.removed.clear();
    as_mapped.objects.clear();
    const TrueWorld mapped(map, as_mapped, dir);
    const Eigen::Vector2d center = (world.removed[0].from + world.removed[0].to) / 2.0;
    EXPECT_EQ(mapped.class_near(center, 0.05), map.class_index("others")) << "seed " << seed;
    EXPECT_EQ(truth.class_near(center, 0.05), -1) << "seed " << seed;
    return;
  }
  FAIL() << "no world of seeds 1-5 removes an object";
}

class ScanSink : public SimulatorSink {
 public:
  void on_scan(const LaserScan& scan, int64_t) override { scans.push_back(scan); }
  void on_encoders(const EncoderSample&) override {}
  void on_odometry(const OdometrySample&) override {}
  void on_ground_truth(const GroundTruthSample&) override {}
  std::vector<LaserScan> scans;
};

std::vector<LaserScan> simulate(const WorldOptions& world, const TrueWorld& truth, int scans) {
  const auto robot = load_options<RobotOptions>(kRobot);
  Simulator sim(truth, world, robot, SimOptions{}, 1);
  ScanSink sink;
  while (static_cast<int>(sink.scans.size()) < scans && sim.step(sink)) {
  }
  return sink.scans;
}

TEST(WorldGen, TheSimulatorFillsIntensitiesFromReflectance) {
  const std::string dir = make_world(4, "intensities");
  auto world = load_options<WorldOptions>(dir + "/world.yaml");
  const SemanticMap map = load_semantic_map(world.map_path);
  const TrueWorld truth(map, world, dir);
  const std::vector<LaserScan> scans = simulate(world, truth, 5);
  ASSERT_EQ(scans.size(), 5u);
  int finite = 0;
  for (std::size_t i = 0; i < scans[0].ranges.size(); ++i) {
    ASSERT_EQ(scans[0].intensities.size(), scans[0].ranges.size());
    const float r = scans[0].ranges[i];
    if (std::isfinite(r)) {
      ++finite;
      // A wall ("others") or door: scale * reflectance / (1 + r / falloff), 2 % noise.
      EXPECT_GT(scans[0].intensities[i], 0.0f);
      EXPECT_LT(scans[0].intensities[i], 10000.0 * 0.8 / (1.0 + r / 5.0) * 1.2);
    } else {
      EXPECT_EQ(scans[0].intensities[i], 0.0f);
    }
  }
  EXPECT_GT(finite, 500);
  world.reflectance.clear();  // a world without materials: no intensities, as before
  const TrueWorld plain(map, world, dir);
  EXPECT_TRUE(simulate(world, plain, 1)[0].intensities.empty());
}

}  // namespace
}  // namespace slamer

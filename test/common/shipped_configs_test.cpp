// Every YAML file shipped in config/ loads with the loader of the program it
// belongs to, and no file is shipped without a loader listed here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"
#include "common/robot/robot_options.hpp"
#include "drivers/urg/urg_options.hpp"
#include "drivers/wheels/wheels_options.hpp"
#include "localizer/class_map_check.hpp"
#include "localizer/localizer_config.hpp"
#include "recognizer/recognizer_config.hpp"
#include "test/support/child_process.hpp"
#include "tools/annotate/object_list.hpp"
#include "tools/eval/eval_config.hpp"
#include "tools/launch/launch_check.hpp"
#include "tools/sim/floor_plan.hpp"
#include "tools/sim/sim_config.hpp"
#include "tools/sim/world.hpp"
#include "tools/status/status_table.hpp"

namespace slamer {
namespace {

// A world loads with everything it names: map, robot, and the truth fitted to the map.
void load_world(const std::string& path) {
  const auto world = load_options<WorldOptions>(path);
  load_options<RobotOptions>(world.robot_path);
  const TrueWorld truth(load_semantic_map(world.map_path), world, path);
  EXPECT_GT(truth.door_count(), 0) << path;
}

void load_map(const std::string& path) {
  const SemanticMap map = load_semantic_map(path);
  EXPECT_TRUE(map.warnings.empty()) << path << ": " << (map.warnings.empty() ? "" : map.warnings[0]);
  EXPECT_EQ(map.unknown_color_cells, 0) << path;
}

// A launch file passes slamer-launch --check: its programs exist (the build's
// bin/ or PATH) and every config and file it names loads with its program's loader.
void check_launch(const std::string& path) {
  const std::vector<std::string> problems =
      launch::check_launch_file(path, {std::string(SLAMER_BINARY_DIR "/bin"), "/usr/bin", "/bin"});
  for (const std::string& problem : problems) {
    ADD_FAILURE() << problem;
  }
}

const std::map<std::string, std::function<void(const std::string&)>>& loaders() {
  static const std::map<std::string, std::function<void(const std::string&)>> table = {
      {"slamer-status.yaml", [](const std::string& path) { load_options<StatusProcessConfig>(path); }},
      {"sim.yaml", [](const std::string& path) { load_options<SimProcessConfig>(path); }},
      {"urg.yaml",
       [](const std::string& path) {
         const auto config = load_options<urg::UrgProcessConfig>(path);
         EXPECT_EQ(config.connection.host, "192.168.0.10");
         EXPECT_EQ(config.connection.port, 10940);
         EXPECT_EQ(config.session.first_step, -1);
         EXPECT_EQ(config.session.last_step, -1);
         EXPECT_EQ(config.session.cluster, 1);
       }},
      {"sim_drivers.yaml",
       [](const std::string& path) {
         // config/sim.yaml with the sensor channels renamed for the device emulators.
         const auto config = load_options<SimProcessConfig>(path);
         const auto plain = load_options<SimProcessConfig>(std::string(SLAMER_SOURCE_DIR "/config/sim.yaml"));
         EXPECT_EQ(config.channels.lidar, "SIM_LIDAR");
         EXPECT_EQ(config.channels.wheel_encoders, "SIM_WHEEL_ENCODERS");
         EXPECT_EQ(config.channels.odometry, "SIM_ODOMETRY");
         EXPECT_EQ(config.channels.ground_truth, "GROUND_TRUTH");
         EXPECT_EQ(config.sim.step, plain.sim.step);
         EXPECT_EQ(config.sim.encoder_period, plain.sim.encoder_period);
         EXPECT_EQ(config.sim.range_stddev, plain.sim.range_stddev);
         EXPECT_EQ(config.sim.dropout_probability, plain.sim.dropout_probability);
         EXPECT_EQ(config.sim.wheel_radius_error_left, plain.sim.wheel_radius_error_left);
         EXPECT_EQ(config.sim.wheel_radius_error_right, plain.sim.wheel_radius_error_right);
         EXPECT_EQ(config.sim.tread_error, plain.sim.tread_error);
         EXPECT_EQ(config.sim.slip_stddev, plain.sim.slip_stddev);
         EXPECT_EQ(config.sim.wheel_slip.turn_slip, plain.sim.wheel_slip.turn_slip);
         EXPECT_EQ(config.sim.wheel_slip.bump_rate, plain.sim.wheel_slip.bump_rate);
       }},
      {"urg_sim.yaml",
       [](const std::string& path) {
         const auto config = load_options<urg::UrgProcessConfig>(path);
         EXPECT_EQ(config.connection.host, "127.0.0.1");
         EXPECT_EQ(config.connection.port, 10940);
         EXPECT_EQ(config.lidar_channel, "LIDAR");
       }},
      {"wheels_sim.yaml",
       [](const std::string& path) {
         const auto config = load_options<WheelsConfig>(path);
         EXPECT_EQ(config.tfrog.device, "/tmp/slamer-tfrog");
         EXPECT_EQ(config.channels.odometry, "ODOMETRY");
       }},
      {"eval.yaml", [](const std::string& path) { load_options<EvalConfig>(path); }},
      {"recognizer.yaml", [](const std::string& path) { load_options<RecognizerProcessConfig>(path); }},
      {"localizer.yaml",
       [](const std::string& path) {
         const auto config = load_options<LocalizerProcessConfig>(path);
         load_semantic_map(config.map);
         load_options<RobotOptions>(config.robot);
       }},
      {"robots/icart_mini.yaml", [](const std::string& path) { load_options<RobotOptions>(path); }},
      {"robots/cmu_wean.yaml", [](const std::string& path) { load_options<RobotOptions>(path); }},
      {"wheels.yaml", [](const std::string& path) { load_options<WheelsConfig>(path); }},
      {"worlds/small_room.yaml", load_world},
      {"worlds/paper_indoor.yaml", load_world},
      {"maps/small_room/plan.yaml", [](const std::string& path) { load_options<FloorPlan>(path); }},
      {"maps/paper_indoor/plan.yaml", [](const std::string& path) { load_options<FloorPlan>(path); }},
      {"maps/small_room/map.yaml", load_map},
      {"maps/paper_indoor/map.yaml", load_map},
      {"launch/sim_direct.yaml", check_launch},
      {"launch/icart_mini.yaml", check_launch},
      {"launch/icart_mini_sim.yaml", check_launch},
      {"maps/examples/small_room_slam.yaml", load_map},
      {"maps/examples/objects_example.yaml",
       [](const std::string& path) {
         const SemanticMap map =
             load_semantic_map((std::filesystem::path(path).parent_path() / "small_room_slam.yaml").string());
         EXPECT_GT(load_object_list(path, map).objects.size(), 0u);
       }},
  };
  return table;
}

TEST(ShippedConfigs, EveryFileLoadsWithItsProgramsLoader) {
  const std::filesystem::path dir = std::filesystem::path(SLAMER_SOURCE_DIR) / "config";
  std::set<std::string> seen;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") {
      continue;
    }
    const std::string name = std::filesystem::relative(entry.path(), dir).string();
    seen.insert(name);
    const auto loader = loaders().find(name);
    ASSERT_NE(loader, loaders().end()) << "config/" << name << " has no loader in " << __FILE__;
    try {
      loader->second(entry.path().string());
    } catch (const ConfigError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  for (const auto& [name, loader] : loaders()) {
    EXPECT_TRUE(seen.count(name) != 0) << "the loader table names config/" << name << ", which does not exist";
  }
}

// The committed map files are exactly what their plan renders to.
// Defaults live in one place: the shipped localizer config states them, and
// the struct's must not silently differ (only the world's start may).
TEST(ShippedConfigs, LocalizerDefaultsAreTheShippedOnes) {
  const auto shipped =
      load_options<LocalizerProcessConfig>(std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml")).localizer;
  const LocalizerOptions defaults;
  EXPECT_EQ(shipped.mode, defaults.mode);
  EXPECT_EQ(shipped.particles, defaults.particles);
  EXPECT_EQ(shipped.seed, defaults.seed);
  EXPECT_EQ(shipped.resample_threshold, defaults.resample_threshold);
  EXPECT_EQ(shipped.initial_sigma, defaults.initial_sigma);
  EXPECT_TRUE(shipped.motion == defaults.motion) << "motion:";
  EXPECT_TRUE(shipped.lfm == defaults.lfm) << "lfm:";
  EXPECT_TRUE(shipped.slfm == defaults.slfm) << "slfm:";
  EXPECT_TRUE(shipped.slamer == defaults.slamer) << "slamer:";
  EXPECT_TRUE(shipped.status == defaults.status) << "status:";
  EXPECT_TRUE(shipped.recovery == defaults.recovery) << "recovery:";
  EXPECT_TRUE(shipped.resume == defaults.resume) << "resume:";
  EXPECT_TRUE(shipped.inputs == defaults.inputs) << "inputs:";
}

// The localizer expects the classes the shipped recognizer emits, and its
// class_map fits the shipped map (the check slamer-localizer runs at start-up).
TEST(ShippedConfigs, LocalizerClassesAreTheRecognizersAndTheMaps) {
  const std::string dir = std::string(SLAMER_SOURCE_DIR "/config/");
  const auto localizer = load_options<LocalizerProcessConfig>(dir + "localizer.yaml");
  const auto recognizer = load_options<RecognizerProcessConfig>(dir + "recognizer.yaml");
  EXPECT_EQ(localizer.localizer.slamer.recognition_classes, recognizer.recognizer.classes);
  EXPECT_EQ(class_map_problem(localizer.localizer, load_semantic_map(localizer.map)), "");
}

TEST(ShippedConfigs, BundledMapsMatchTheirPlans) {
  for (const std::string name : {"small_room", "paper_indoor"}) {
    const std::filesystem::path dir = std::filesystem::path(SLAMER_SOURCE_DIR) / "config/maps" / name;
    const std::filesystem::path out = std::filesystem::temp_directory_path() / ("slamer_plan_" + name);
    std::filesystem::create_directories(out);
    write_floor_plan_map(load_options<FloorPlan>((dir / "plan.yaml").string()), out.string());
    for (const char* file : {"map.pgm", "semantic.png", "map.yaml"}) {
      EXPECT_EQ(test::read_file(out / file), test::read_file(dir / file))
          << "config/maps/" << name << "/" << file << " is stale: run slamer-make-map plan.yaml . in its folder";
    }
    std::filesystem::remove_all(out);
  }
}

}  // namespace
}  // namespace slamer

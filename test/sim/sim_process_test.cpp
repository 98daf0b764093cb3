// slamer-sim as a program: the same seed writes a byte-identical log, another
// seed a different one, and the log holds every channel at its rate.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <nlohmann/json.hpp>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

int run_sim(const std::string& seed, const std::string& out) {
  test::ChildProcess sim(test::binary_path("slamer-sim"),
                         {"--world", std::string(SLAMER_SOURCE_DIR "/config/worlds/small_room.yaml"), "--config",
                          std::string(SLAMER_SOURCE_DIR "/config/sim.yaml"), "--seed", seed, "--out", out});
  const std::optional<int> code = sim.wait(60.0);
  EXPECT_TRUE(code.has_value());
  EXPECT_EQ(code.value_or(-1), 0) << sim.stderr_text();
  return code.value_or(-1);
}

TEST(SlamerSim, LogsAreByteIdenticalForASeed) {
  const std::string dir = std::string(SLAMER_BINARY_DIR);
  const std::string a = dir + "/sim_a.lcm";
  const std::string b = dir + "/sim_b.lcm";
  const std::string c = dir + "/sim_c.lcm";
  ASSERT_EQ(run_sim("5", a), 0);
  ASSERT_EQ(run_sim("5", b), 0);
  ASSERT_EQ(run_sim("6", c), 0);
  const std::string bytes = test::read_file(a);
  EXPECT_GT(bytes.size(), 1'000'000u);
  EXPECT_TRUE(bytes == test::read_file(b)) << "two runs with seed 5 differ";
  EXPECT_FALSE(bytes == test::read_file(c)) << "seeds 5 and 6 gave the same log";

  lcm::LogFile log(a, "r");
  std::map<std::string, int> counts;
  int64_t last = 0;
  bool ordered = true;
  for (const lcm::LogEvent* event = log.readNextEvent(); event != nullptr; event = log.readNextEvent()) {
    ++counts[event->channel];
    ordered = ordered && event->timestamp >= last;
    last = event->timestamp;
  }
  EXPECT_TRUE(ordered) << "log timestamps go backwards";
  EXPECT_GT(counts["LIDAR"], 400);
  EXPECT_EQ(counts["GROUND_TRUTH"], counts["LIDAR"]);
  EXPECT_NEAR(counts["ODOMETRY"], counts["LIDAR"] * 2.5, counts["LIDAR"] * 0.05);
  EXPECT_EQ(counts["WHEEL_ENCODERS"], counts["ODOMETRY"]);
  for (const std::string& f : {a, b, c}) {
    std::remove(f.c_str());
  }
}

TEST(SlamerSim, BadWorldFileIsOneLine) {
  test::ChildProcess sim(test::binary_path("slamer-sim"),
                         {"--world", "/nonexistent/world.yaml", "--out", "/tmp/x.lcm"});
  EXPECT_EQ(sim.wait(10.0), std::optional<int>(1));
  EXPECT_EQ(sim.stderr_text(),
            "slamer-sim: config error: /nonexistent/world.yaml: cannot open: No such file or directory\n");
  test::ChildProcess no_world(test::binary_path("slamer-sim"), {"--out", "/tmp/x.lcm"});
  EXPECT_EQ(no_world.wait(10.0), std::optional<int>(2));
  EXPECT_EQ(no_world.stderr_text(), "slamer-sim: error: --world FILE is required\n");
}

}  // namespace
}  // namespace slamer

namespace slamer {
namespace {

// slamer-sim -> slamer-eval: ground truth as the estimate scores zero error,
// dead reckoning does not.
TEST(SlamerEval, GroundTruthScoresZeroAndOdometryDrifts) {
  const std::string log = std::string(SLAMER_BINARY_DIR "/sim_eval.lcm");
  ASSERT_EQ(run_sim("3", log), 0);
  const std::string world = std::string(SLAMER_SOURCE_DIR "/config/worlds/small_room.yaml");
  const std::string config = std::string(SLAMER_SOURCE_DIR "/config/eval.yaml");
  test::ChildProcess truth(test::binary_path("slamer-eval"),
                           {"--world", world, "--config", config, "--estimate", "GROUND_TRUTH", "--json", log});
  ASSERT_EQ(truth.wait(60.0), std::optional<int>(0)) << truth.stderr_text();
  const nlohmann::json pose = nlohmann::json::parse(truth.stdout_text()).at("runs").at(0).at("pose");
  EXPECT_EQ(pose.at("position_mean_m").get<double>(), 0.0) << pose.dump();
  EXPECT_EQ(pose.at("position_std_m").get<double>(), 0.0) << pose.dump();
  EXPECT_EQ(pose.at("position_max_m").get<double>(), 0.0) << pose.dump();
  const std::string plot = std::string(SLAMER_BINARY_DIR "/sim_eval.png");
  test::ChildProcess odometry(test::binary_path("slamer-eval"),
                              {"--world", world, "--estimate", "ODOMETRY", "--plot", plot, log});
  ASSERT_EQ(odometry.wait(60.0), std::optional<int>(0)) << odometry.stderr_text();
  const std::string table = odometry.stdout_text();
  const std::size_t row = table.find("Pose error [cm / deg]  Ave");
  ASSERT_NE(row, std::string::npos) << table;
  const double mean_cm = std::stod(table.substr(table.find_first_of("0123456789", row + 28)));
  EXPECT_GT(mean_cm, 0.5) << table;
  EXPECT_LT(mean_cm, 300.0) << table;  // config/sim.yaml is an uncalibrated robot: 3-5 deg per metre
  EXPECT_GT(std::filesystem::file_size(plot), 1000u);
  std::remove(log.c_str());
  std::remove(plot.c_str());
}

}  // namespace
}  // namespace slamer

namespace slamer {
namespace {

TEST(SlamerRender, WritesFramesOfALog) {
  const std::string log = std::string(SLAMER_BINARY_DIR "/sim_render.lcm");
  ASSERT_EQ(run_sim("4", log), 0);
  const std::string out = std::string(SLAMER_BINARY_DIR "/render_frames");
  std::filesystem::remove_all(out);
  test::ChildProcess render(test::binary_path("slamer-render"),
                            {"--world", std::string(SLAMER_SOURCE_DIR "/config/worlds/small_room.yaml"), "--out", out,
                             "--every", "200", "--max-frames", "3", log});
  ASSERT_EQ(render.wait(60.0), std::optional<int>(0)) << render.stderr_text();
  EXPECT_TRUE(std::filesystem::exists(out + "/frame_000000.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/frame_000002.png"));
  EXPECT_FALSE(std::filesystem::exists(out + "/frame_000003.png"));
  EXPECT_GT(std::filesystem::file_size(out + "/frame_000000.png"), 2000u);
  std::filesystem::remove_all(out);
  std::remove(log.c_str());
}

}  // namespace
}  // namespace slamer

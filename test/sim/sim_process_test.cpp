// slamer-sim as a program: the same seed writes a byte-identical log, another
// seed a different one, and the log holds every channel at its rate.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int run_sim(const std::string& seed, const std::string& out) {
  test::ChildProcess sim(test::binary_path("slamer-sim"),
                         {"--world", std::string(SLAMER_SOURCE_DIR) + "/config/worlds/small_room.yaml", "--config",
                          std::string(SLAMER_SOURCE_DIR) + "/config/sim.yaml", "--seed", seed, "--out", out});
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
  const std::string bytes = read_bytes(a);
  EXPECT_GT(bytes.size(), 1'000'000u);
  EXPECT_TRUE(bytes == read_bytes(b)) << "two runs with seed 5 differ";
  EXPECT_FALSE(bytes == read_bytes(c)) << "seeds 5 and 6 gave the same log";

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

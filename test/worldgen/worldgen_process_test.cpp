// slamer-gen-world and slamer-sim as programs: a generated world (short route)
// is driven by the simulator, whose scans carry intensities.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "slamer/laser_scan_t.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

int run(const std::string& program, const std::vector<std::string>& args, double timeout = 60.0) {
  test::ChildProcess child(test::binary_path(program), args);
  const std::optional<int> code = child.wait(timeout);
  EXPECT_EQ(code.value_or(-1), 0) << program << ": " << child.stderr_text();
  return code.value_or(-1);
}

TEST(SlamerGenWorld, TheSimulatorDrivesAGeneratedWorld) {
  const std::string dir = std::string(SLAMER_BINARY_DIR "/worldgen_process_test");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/short.yaml") << "route: {rooms_min: 1, rooms_max: 1, corridor_fraction: 0.3}\n";
  ASSERT_EQ(run("slamer-gen-world", {"--seed", "5", "--out", dir + "/world", "--config", dir + "/short.yaml"}), 0);
  ASSERT_EQ(
      run("slamer-sim", {"--world", dir + "/world/world.yaml", "--config",
                         std::string(SLAMER_SOURCE_DIR "/config/sim.yaml"), "--seed", "1", "--out", dir + "/run.lcm"}),
      0);
  lcm::LogFile log(dir + "/run.lcm", "r");
  std::map<std::string, int> counts;
  int with_intensities = 0;
  for (const lcm::LogEvent* event = log.readNextEvent(); event != nullptr; event = log.readNextEvent()) {
    ++counts[event->channel];
    if (event->channel == "LIDAR") {
      laser_scan_t scan;
      ASSERT_GT(scan.decode(event->data, 0, event->datalen), 0);
      with_intensities += scan.nintensities == scan.nranges ? 1 : 0;
    }
  }
  EXPECT_GT(counts["LIDAR"], 400);  // more than 10 s of driving
  EXPECT_EQ(with_intensities, counts["LIDAR"]);
  EXPECT_EQ(counts["GROUND_TRUTH"], counts["LIDAR"]);
}

TEST(SlamerGenWorld, MissingOutIsOneLine) {
  test::ChildProcess child(test::binary_path("slamer-gen-world"), {"--seed", "1"});
  EXPECT_EQ(child.wait(10.0).value_or(-1), 2);
  EXPECT_NE(child.stderr_text().find("--out DIR is required"), std::string::npos) << child.stderr_text();
}

}  // namespace
}  // namespace slamer

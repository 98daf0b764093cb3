// Global localization on a real log with no reference: CMU Wean Hall
// robotdata1 through the real programs, as tools/datasets/wean_global.sh runs
// it (slamer-mapgen --wean, slamer-carmen2lcm --format cmu, slamer-localizer
// --global with the shipped config at 5000 particles, every beam). Wean has no
// ground truth: "home" is where log 1's agreeing runs end, within 1 m of where
// those of logs 3 and 4 do, the spot the robot is kept (README, "Real recorded
// logs": the Wean tables).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

constexpr double kHomeX = 39.9;  // [m] log 1's home spot
constexpr double kHomeY = 41.5;

// The last POSE of a localizer's output log.
pose_estimate_t last_pose(const std::string& path) {
  pose_estimate_t last;
  EventLogReader reader(path);
  while (const auto event = reader.next()) {
    if (event->channel == "POSE") {
      pose_estimate_t m;
      if (decode_message(event->data.data(), event->data.size(), &m) == DecodeStatus::kOk) {
        last = m;
      }
    }
  }
  return last;
}

// Log 1 drives west along a corridor whose doors and bays repeat 14 m east.
// Each kept place was scored at its best pose within 0.5 m at every weighing,
// free of the odometry: in seed 2 the look-alike slid back along its corridor
// scan after scan, stood still while the robot drove 8 m and overtook home at
// scan 405; seeds 1-3 ended 18-31 m away, and none of seeds 1-12 home. With a
// prior on that offset 10 of seeds 1-12 end home, the other two 0.9-1.3 m off.
TEST(WeanGlobalLocalization, Log1EndsAtTheHomeSpotInTwoOfThreeSeeds) {
  const std::string data = std::string(SLAMER_SOURCE_DIR) + "/../shared/datasets/cmu_wean_16831/";
  if (!std::filesystem::exists(data + "robotdata1.log.gz")) {
    GTEST_SKIP() << "../shared/datasets/cmu_wean_16831 is absent";
  }
  const std::string dir = (std::filesystem::temp_directory_path() / "slamer_wean_global_test").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  test::ChildProcess mapgen(test::binary_path("slamer-mapgen"), {"--wean", data + "wean.dat.gz", dir + "/map"});
  ASSERT_EQ(mapgen.wait(60), 0) << mapgen.stderr_text();
  test::ChildProcess convert(test::binary_path("slamer-carmen2lcm"),
                             {data + "robotdata1.log.gz", dir + "/log1.lcm", "--format", "cmu"});
  ASSERT_EQ(convert.wait(60), 0) << convert.stderr_text();
  // The shipped config at 5000 particles, as the script's sed makes it (no std::regex: under
  // the sanitizers GCC 12 warns a false -Wmaybe-uninitialized inside it).
  std::string config = test::read_file(std::string(SLAMER_SOURCE_DIR) + "/config/localizer.yaml");
  const std::string key = "\n  particles: ";
  const std::size_t at = config.find(key, config.find("\nlocalizer:"));  // not the channel of that name
  ASSERT_NE(at, std::string::npos);
  const std::size_t value = at + key.size();
  config.replace(value, config.find_first_not_of("0123456789", value) - value, "5000");
  ASSERT_EQ(config.compare(at, key.size() + 5, key + "5000\n"), 0);
  {
    std::ofstream out(dir + "/localizer.yaml");
    out << config;
  }
  int home = 0;
  std::string ends;
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string run = dir + "/run" + std::to_string(seed) + ".lcm";
    test::ChildProcess localizer(
        test::binary_path("slamer-localizer"),
        {"--config", dir + "/localizer.yaml", "--map", dir + "/map/map.yaml", "--robot",
         std::string(SLAMER_SOURCE_DIR) + "/config/robots/cmu_wean.yaml", "--mode", "lfm", "--seed",
         std::to_string(seed), "--global", "--replay", dir + "/log1.lcm", "--out", run});
    ASSERT_EQ(localizer.wait(120), 0) << localizer.stderr_text();
    const pose_estimate_t end = last_pose(run);
    const double off = std::hypot(end.x - kHomeX, end.y - kHomeY);
    home += off < 0.5 ? 1 : 0;
    ends += " " + std::to_string(off);
  }
  RecordProperty("end_offsets_m", ends);
  // Measured: 0.04 and 0.08 m (seeds 1, 2), 1.31 m (seed 3, never settled);
  // before the prior 31.0, 18.3 and 18.1 m.
  EXPECT_GE(home, 2) << "metres from home at the end:" << ends;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slamer

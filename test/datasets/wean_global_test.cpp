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
#include <string>
#include <vector>

#include "test/support/child_process.hpp"
#include "test/support/temp_dir.hpp"
#include "tools/datasets/bench_files.hpp"

namespace slamer {
namespace {

constexpr double kHomeX = 39.9;  // [m] log 1's home spot
constexpr double kHomeY = 41.5;

// Log 1 drives west along a corridor whose doors and bays repeat 14 m east.
// Each kept place was scored at its best pose within 0.5 m at every weighing,
// free of the odometry: in seed 2 the look-alike slid back along its corridor
// scan after scan, stood still while the robot drove 8 m and overtook home at
// scan 405; seeds 1-3 ended 18-31 m away, and none of seeds 1-12 home. With a
// prior on that offset 10 of seeds 1-12 end home, the other two 0.9-1.3 m off.
TEST(WeanGlobalLocalization, Log1EndsAtTheHomeSpotInTwoOfThreeSeeds) {
  const std::string data = std::string(SLAMER_SOURCE_DIR "/../shared/datasets/cmu_wean_16831/");
  if (!std::filesystem::exists(data + "robotdata1.log.gz")) {
    GTEST_SKIP() << "../shared/datasets/cmu_wean_16831 is absent";
  }
  const test::TempDir temp("slamer_wean_global_test");
  const std::string& dir = temp.path();
  test::ChildProcess mapgen(test::binary_path("slamer-mapgen"), {"--wean", data + "wean.dat.gz", dir + "/map"});
  ASSERT_EQ(mapgen.wait(60), 0) << mapgen.stderr_text();
  test::ChildProcess convert(test::binary_path("slamer-carmen2lcm"),
                             {data + "robotdata1.log.gz", dir + "/log1.lcm", "--format", "cmu"});
  ASSERT_EQ(convert.wait(60), 0) << convert.stderr_text();
  // The shipped config at 5000 particles and every beam, as slamer-bench writes its own.
  const std::string robot = std::string(SLAMER_SOURCE_DIR "/config/robots/cmu_wean.yaml");
  write_text_file(dir + "/localizer.yaml",
                  bench_localizer_config(std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml"),
                                         {5000, 1, dir + "/map/map.yaml", robot}));
  int home = 0;
  std::string ends;
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string run = dir + "/run" + std::to_string(seed) + ".lcm";
    test::ChildProcess localizer(
        test::binary_path("slamer-localizer"),
        {"--config", dir + "/localizer.yaml", "--map", dir + "/map/map.yaml", "--robot", robot, "--mode", "lfm",
         "--seed", std::to_string(seed), "--global", "--replay", dir + "/log1.lcm", "--out", run});
    ASSERT_EQ(localizer.wait(120), 0) << localizer.stderr_text();
    const std::vector<PoseReport> poses = read_pose_reports(run, "POSE");
    ASSERT_FALSE(poses.empty()) << run;
    const double off = std::hypot(poses.back().pose.x - kHomeX, poses.back().pose.y - kHomeY);
    home += off < 0.5 ? 1 : 0;
    ends += " " + std::to_string(off);
  }
  RecordProperty("end_offsets_m", ends);
  // Measured: 0.04 and 0.08 m (seeds 1, 2), 1.31 m (seed 3, never settled);
  // before the prior 31.0, 18.3 and 18.1 m.
  EXPECT_GE(home, 2) << "metres from home at the end:" << ends;
}

}  // namespace
}  // namespace slamer

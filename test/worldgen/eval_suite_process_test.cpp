// slamer-eval-suite as a program: 3 generated test worlds with short routes
// through the whole offline pipeline, each localized with 2 localizer seeds,
// the tables and matrices printed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

TEST(SlamerEvalSuite, ThreeShortWorlds) {
  const std::string dir = std::string(SLAMER_BINARY_DIR "/eval_suite_process_test");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/short.yaml") << "corridor: {length_min: 14, length_max: 20}\n"
                                     << "route: {rooms_min: 1, rooms_max: 1, corridor_fraction: 0.3}\n";
  test::ChildProcess suite(
      test::binary_path("slamer-eval-suite"),
      {"--worlds", "3", "--seed", "0", "--out", dir + "/out", "--gen-config", dir + "/short.yaml", "--jobs", "3",
       "--localizer-seeds", "2", "--config", std::string(SLAMER_SOURCE_DIR "/config/eval.yaml")});
  ASSERT_EQ(suite.wait(170.0).value_or(-1), 0) << suite.stderr_text();
  const std::string out = suite.stdout_text();
  for (const std::string world : {"100000", "100001", "100002"}) {
    EXPECT_NE(out.find("=== world " + world + ":"), std::string::npos) << out;
    EXPECT_NE(out.find("=== world " + world + ", localizer seed 2:"), std::string::npos) << out;
    EXPECT_NE(out.find("\n" + world + "/2 "), std::string::npos) << "a summary row per localizer seed";
    EXPECT_TRUE(std::filesystem::exists(dir + "/out/world_" + world + "/world/differences.yaml"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/world_" + world + "/sim.lcm")) << "logs are not kept";
  }
  EXPECT_NE(out.find("Pose error [cm / deg]  Ave"), std::string::npos);
  EXPECT_NE(out.find("slamer-s2.lcm"), std::string::npos) << "the seed-2 runs' column names";
  EXPECT_NE(out.find("of 3 worlds"), std::string::npos) << "the goals count worlds, not runs";
  for (const std::string title : {"Recognizer (rows", "Map-based (SLAMER's pose) (rows", "SLAMER (rows"}) {
    EXPECT_NE(out.find(title), std::string::npos) << title;
  }
  // The mean row: SLAMER's pose error tracks (under 30 cm) and its ER Acc is a percentage.
  // (Parsed by hand: GCC 12 warns inside <regex> under -O1 with the sanitizers.)
  const std::size_t row = out.find("\nmean ");
  ASSERT_NE(row, std::string::npos) << out;
  std::istringstream fields(out.substr(row + 6, out.find('\n', row + 1) - row - 6));
  std::vector<double> mean;
  for (double v = 0.0; fields >> v;) {
    mean.push_back(v);
  }
  ASSERT_GE(mean.size(), 8u) << out;
  EXPECT_LT(mean[2], 30.0);
  EXPECT_GT(mean[7], 50.0);
  EXPECT_LE(mean[7], 100.0);
  EXPECT_EQ(test::read_file(dir + "/out/summary.txt"), out);
}

// A bad --localizer-seeds stops the suite at once with one line naming the flag.
TEST(SlamerEvalSuite, RefusesLocalizerSeedsOutOfRange) {
  for (const std::string bad : {"0", "101", "-2"}) {
    test::ChildProcess suite(test::binary_path("slamer-eval-suite"), {"--localizer-seeds", bad});
    ASSERT_EQ(suite.wait(10.0).value_or(-1), 2) << bad << ": " << suite.stderr_text();
    EXPECT_NE(suite.stderr_text().find("--localizer-seeds in 1..100"), std::string::npos) << suite.stderr_text();
  }
}

}  // namespace
}  // namespace slamer

// slamer-calibrate-recognizer as a program: training worlds it generates and
// simulates itself (short routes), the rules and the recognition model fitted,
// the same for the same seed, and usable as the recognizer's config.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;

TEST(SlamerCalibrateRecognizer, FitsOnGeneratedTrainingWorldsTheSameForASeed) {
  const std::string dir = std::string(SLAMER_BINARY_DIR "/calibrate_process_test");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/short.yaml") << "corridor: {length_min: 14, length_max: 20}\n"
                                     << "route: {rooms_min: 1, rooms_max: 1, corridor_fraction: 0.3}\n";
  const std::vector<std::string> args{"--config",       kSource + "/config/recognizer.yaml",
                                      "--eval-config",  kSource + "/config/eval.yaml",
                                      "--train-worlds", "2",
                                      "--seed",         "3",
                                      "--gen-config",   dir + "/short.yaml",
                                      "--out",          dir + "/worlds"};
  test::ChildProcess first(test::binary_path("slamer-calibrate-recognizer"), args);
  ASSERT_EQ(first.wait(170.0).value_or(-1), 0) << first.stderr_text();
  // Training seeds 1000 S + 1 + k: below the test worlds' 100000.
  for (const std::string seed : {"3001", "3002"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/worlds/train_" + seed + "/sim.lcm")) << seed;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/worlds/train_3003"));
  const std::string fitted = first.stdout_text();
  EXPECT_NE(fitted.find("  rules:   # fitted by slamer-calibrate-recognizer on "), std::string::npos) << fitted;
  EXPECT_NE(fitted.find("    dirichlet_a1: "), std::string::npos) << fitted;
  EXPECT_NE(fitted.find("fitted on worlds the rules were not fitted on"), std::string::npos) << fitted;
  EXPECT_NE(first.stderr_text().find(" in 2 worlds; most likely class right: "), std::string::npos)
      << first.stderr_text();

  // Again (the worlds' logs reused): the same fit.
  test::ChildProcess second(test::binary_path("slamer-calibrate-recognizer"), args);
  ASSERT_EQ(second.wait(170.0).value_or(-1), 0) << second.stderr_text();
  EXPECT_EQ(second.stdout_text(), fitted);

  // The rules as a recognizer config: the recognizer's loader takes them.
  const std::string shipped = test::read_file(kSource + "/config/recognizer.yaml");
  const std::string config = dir + "/recognizer.yaml";
  std::ofstream(config) << shipped.substr(0, shipped.find("  rules:")) << fitted.substr(0, fitted.find("# config/"));
  test::ChildProcess check(
      test::binary_path("slamer-recognizer"),
      {"--config", config, "--replay", dir + "/worlds/train_3001/sim.lcm", "--out", dir + "/recognized.lcm"});
  EXPECT_EQ(check.wait(120.0).value_or(-1), 0) << check.stderr_text();
}

// Apart from the fit (which CI leaves out of the sanitizer run for its length), so the
// program's own argument handling still runs under the sanitizers.
TEST(SlamerCalibrateRecognizer, WithNothingToFitOnSaysSoInOneLine) {
  test::ChildProcess neither(test::binary_path("slamer-calibrate-recognizer"),
                             {"--config", kSource + "/config/recognizer.yaml"});
  EXPECT_EQ(neither.wait(30.0).value_or(-1), 2);
  const std::string error = neither.stderr_text();
  EXPECT_NE(error.find("nothing to fit on"), std::string::npos) << error;
  EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << error;
}

}  // namespace
}  // namespace slamer

// slamer-localizer as a program: an offline replay is byte-identical for a
// seed, replaces earlier outputs, scores on the small world, and reads a
// damaged log around the damage; bad input to the command line gives one line.
#include <gtest/gtest.h>

#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBinary = SLAMER_BINARY_DIR;

int run(const std::string& program, const std::vector<std::string>& args, std::string* err = nullptr) {
  test::ChildProcess child(test::binary_path(program), args);
  const std::optional<int> code = child.wait(240.0);
  if (err != nullptr) {
    *err = child.stderr_text();
  }
  EXPECT_TRUE(code.has_value()) << program << " did not finish";
  return code.value_or(-1);
}

std::map<std::string, int> channel_counts(const std::string& path) {
  lcm::LogFile log(path, "r");
  std::map<std::string, int> counts;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    ++counts[e->channel];
  }
  return counts;
}

TEST(SlamerLocalizer, ReplayIsDeterministicAndLocalizesTheSmallWorld) {
  const std::string sim_config = kBinary + "/loc_sim.yaml";
  std::ofstream(sim_config) << "sim: {max_duration: 12.0}\n";
  const std::string sensors = kBinary + "/loc_sensors.lcm";
  const std::string recognized = kBinary + "/loc_recognized.lcm";
  ASSERT_EQ(run("slamer-sim", {"--world", kSource + "/config/worlds/small_room.yaml", "--config", sim_config, "--seed",
                               "2", "--out", sensors}),
            0);
  ASSERT_EQ(run("slamer-recognizer",
                {"--config", kSource + "/config/recognizer.yaml", "--replay", sensors, "--out", recognized}),
            0);
  // The shipped localizer config is for the paper world: point it at the small room.
  const std::string config = kBinary + "/loc_config.yaml";
  std::ofstream(config)
      << "map: " << kSource << "/config/maps/small_room/map.yaml\nrobot: " << kSource
      << "/config/robots/icart_mini.yaml\nlocalizer: {particles: 200, initial_pose: [1.5, 3.0, 0.0]}\n";
  std::vector<std::string> outputs;
  for (const std::string name : {"a", "b"}) {
    const std::string out = kBinary + "/loc_" + name + ".lcm";
    std::string err;
    ASSERT_EQ(run("slamer-localizer",
                  {"--config", config, "--mode", "slamer", "--seed", "4", "--replay", recognized, "--out", out}, &err),
              0)
        << err;
    outputs.push_back(out);
  }
  EXPECT_TRUE(test::read_file(outputs[0]) == test::read_file(outputs[1])) << "two replays with one seed differ";
  const auto counts = channel_counts(outputs[0]);
  EXPECT_EQ(counts.at("POSE"), counts.at("LIDAR"));
  EXPECT_EQ(counts.at("SEMANTIC_OBJECTS"), counts.at("LIDAR"));
  EXPECT_GT(counts.at("PARTICLES"), 10);
  EXPECT_EQ(counts.at("LINE_OBJECTS"), counts.at("LIDAR"));

  // Replaying the output again replaces its POSE instead of doubling it.
  const std::string again = kBinary + "/loc_again.lcm";
  ASSERT_EQ(run("slamer-localizer", {"--config", config, "--replay", outputs[0], "--out", again}), 0);
  EXPECT_EQ(channel_counts(again).at("POSE"), counts.at("LIDAR"));

  test::ChildProcess eval(test::binary_path("slamer-eval"),
                          {"--world", kSource + "/config/worlds/small_room.yaml", "--json", outputs[0]});
  ASSERT_EQ(eval.wait(60.0), std::optional<int>(0)) << eval.stderr_text();
  const std::string json = eval.stdout_text();
  const std::size_t at = json.find("\"position_mean_m\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_LT(std::stod(json.substr(at + 19)), 0.10) << json;
  EXPECT_NE(json.find("\"lost_fraction\": 0}"), std::string::npos) << json;
  // A damaged copy (a stretch of zeros in the middle): replayed around the damage, said in one line.
  const std::string damaged = kBinary + "/loc_damaged.lcm";
  const std::string damaged_out = kBinary + "/loc_damaged_out.lcm";
  std::string bytes = test::read_file(recognized);
  std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2), 3000, '\0');
  std::ofstream(damaged, std::ios::binary) << bytes;
  std::string err;
  ASSERT_EQ(run("slamer-localizer", {"--config", config, "--replay", damaged, "--out", damaged_out}, &err), 0) << err;
  EXPECT_NE(err.find("WARN " + damaged + ": skipped "), std::string::npos) << err;
  EXPECT_NE(err.find(" damaged bytes in 1 place(s)\n"), std::string::npos) << err;
  const auto damaged_counts = channel_counts(damaged_out);
  EXPECT_GE(damaged_counts.at("POSE"), counts.at("LIDAR") - 3);  // 3000 bytes: at most a few events
  EXPECT_EQ(damaged_counts.at("POSE"), damaged_counts.at("LIDAR"));
  for (const std::string& f : {sensors, recognized, outputs[0], outputs[1], again, damaged, damaged_out}) {
    std::remove(f.c_str());
  }
}

TEST(SlamerLocalizer, BadArgumentsAndMissingMapAreOneLine) {
  std::string err;
  EXPECT_EQ(run("slamer-localizer", {"--mode", "amcl", "--replay", "x", "--out", "y"}, &err), 2);
  EXPECT_EQ(err, "slamer-localizer: error: option '--mode': mode must be lfm, slfm or slamer, got 'amcl'\n");
  EXPECT_EQ(run("slamer-localizer", {"--replay", "x.lcm", "--out", "y.lcm"}, &err), 1);
  EXPECT_EQ(err, "slamer-localizer: config error: no map: set 'map' in the config or pass --map\n");
  EXPECT_EQ(run("slamer-localizer", {"--map", "/nonexistent/map.yaml", "--replay", "x", "--out", "y"}, &err), 1);
  EXPECT_EQ(err, "slamer-localizer: config error: /nonexistent/map.yaml: cannot open: No such file or directory\n");
}

}  // namespace
}  // namespace slamer

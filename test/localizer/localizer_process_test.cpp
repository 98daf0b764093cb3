// slamer-localizer as a program: an offline replay is byte-identical for a
// seed, replaces earlier outputs, carries its PROCESS_STATUS, scores on the
// small world, and reads a damaged log around the damage; bad input to the
// command line, and what is not a log, give one line.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <nlohmann/json.hpp>

#include "common/process/decode.hpp"
#include "slamer/process_status_t.hpp"
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

// The programs' sizes and times: a fixture made by other binaries is made again.
std::string binaries_stamp() {
  std::string stamp;
  for (const std::string name : {"slamer-sim", "slamer-recognizer", "slamer-localizer"}) {
    const auto path = test::binary_path(name);
    stamp += name + " " + std::to_string(std::filesystem::file_size(path)) + " " +
             std::to_string(std::filesystem::last_write_time(path).time_since_epoch().count()) + "\n";
  }
  return stamp;
}

// One simulated and recognized drive through the small room, and one replay
// of it, shared by the tests below. ctest runs each test in its own process,
// in parallel: the first makes the files under a lock, the others reuse them.
class SlamerLocalizerReplay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const int lock = open((kBinary + "/loc_fixture.lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
    ASSERT_GE(lock, 0);
    ASSERT_EQ(flock(lock, LOCK_EX), 0);
    const std::string marker = kBinary + "/loc_fixture.done";
    if (test::read_file(marker) != binaries_stamp()) {
      make();
      std::ofstream(marker) << binaries_stamp();
    }
    flock(lock, LOCK_UN);
    close(lock);
  }
  static void make() {
    std::ofstream(kBinary + "/loc_sim.yaml") << "sim: {max_duration: 12.0}\n";
    ASSERT_EQ(run("slamer-sim", {"--world", kSource + "/config/worlds/small_room.yaml", "--config",
                                 kBinary + "/loc_sim.yaml", "--seed", "2", "--out", sensors()}),
              0);
    ASSERT_EQ(run("slamer-recognizer",
                  {"--config", kSource + "/config/recognizer.yaml", "--replay", sensors(), "--out", recognized()}),
              0);
    // The shipped localizer config is for the paper world: point it at the small room.
    std::ofstream(config()) << "map: " << kSource << "/config/maps/small_room/map.yaml\nrobot: " << kSource
                            << "/config/robots/icart_mini.yaml\nlocalizer: {particles: 200, initial_pose: [1.5, 3.0, "
                               "0.0]}\n";
    ASSERT_EQ(localize(recognized(), output()), 0);
  }
  static std::string sensors() { return kBinary + "/loc_sensors.lcm"; }
  static std::string recognized() { return kBinary + "/loc_recognized.lcm"; }
  static std::string output() { return kBinary + "/loc_a.lcm"; }
  static std::string config() { return kBinary + "/loc_config.yaml"; }
  static int localize(const std::string& in, const std::string& out, std::string* err = nullptr) {
    return run("slamer-localizer",
               {"--config", config(), "--mode", "slamer", "--seed", "4", "--replay", in, "--out", out}, err);
  }
};

TEST_F(SlamerLocalizerReplay, IsByteIdenticalForASeed) {
  const std::string again = kBinary + "/loc_b.lcm";
  std::string err;
  ASSERT_EQ(localize(recognized(), again, &err), 0) << err;
  EXPECT_TRUE(test::read_file(output()) == test::read_file(again)) << "two replays with one seed differ";
  std::remove(again.c_str());
}

TEST_F(SlamerLocalizerReplay, GivesOnePoseAndObjectsPerScan) {
  const auto counts = channel_counts(output());
  EXPECT_EQ(counts.at("POSE"), counts.at("LIDAR"));
  EXPECT_EQ(counts.at("SEMANTIC_OBJECTS"), counts.at("LIDAR"));
  EXPECT_EQ(counts.at("LINE_OBJECTS"), counts.at("LIDAR"));
  EXPECT_GT(counts.at("PARTICLES"), 10);
}

TEST_F(SlamerLocalizerReplay, ReplayingItsOwnOutputReplacesThePoses) {
  const std::string again = kBinary + "/loc_again.lcm";
  ASSERT_EQ(localize(output(), again), 0);
  EXPECT_EQ(channel_counts(again).at("POSE"), channel_counts(output()).at("LIDAR"));
  std::remove(again.c_str());
}

TEST_F(SlamerLocalizerReplay, WritesItsProcessStatusWithItsCounters) {
  lcm::LogFile log(output(), "r");
  std::vector<process_status_t> statuses;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    process_status_t status{};
    if (e->channel == "PROCESS_STATUS" &&
        decode_message(e->data, static_cast<std::size_t>(e->datalen), &status) == DecodeStatus::kOk &&
        status.process == "slamer-localizer") {
      statuses.push_back(status);
    }
  }
  ASSERT_GE(statuses.size(), 12u);  // 12 s of log: one a second, and the last
  const process_status_t& last = statuses.back();
  int64_t lidar_in = -1;
  int64_t pose_out = -1;
  for (const channel_stats_t& c : last.channels) {
    if (c.channel == "LIDAR" && c.direction == channel_stats_t::SUBSCRIBED) {
      lidar_in = c.messages;
    }
    if (c.channel == "POSE" && c.direction == channel_stats_t::PUBLISHED) {
      pose_out = c.messages;
    }
  }
  EXPECT_EQ(lidar_in, channel_counts(output()).at("LIDAR"));
  EXPECT_EQ(pose_out, lidar_in);
  EXPECT_EQ(last.drops, 0);
  EXPECT_EQ(last.decode_errors, 0);
  EXPECT_EQ(last.pid, 0);  // a replay's status is deterministic
}

TEST_F(SlamerLocalizerReplay, LocalizesTheSmallWorldWithinTenCentimetres) {
  test::ChildProcess eval(test::binary_path("slamer-eval"),
                          {"--world", kSource + "/config/worlds/small_room.yaml", "--json", output()});
  ASSERT_EQ(eval.wait(60.0), std::optional<int>(0)) << eval.stderr_text();
  const nlohmann::json report = nlohmann::json::parse(eval.stdout_text());
  ASSERT_TRUE(report.contains("runs")) << report.dump();
  const nlohmann::json& pose = report.at("runs").at(0).at("pose");
  EXPECT_LT(pose.at("position_mean_m").get<double>(), 0.10) << pose.dump();
  EXPECT_EQ(pose.at("lost_fraction").get<double>(), 0.0) << pose.dump();
}

// --global: the robot may be anywhere; a start pose given as well (here 2.8 m
// and 115 deg off) is not used.
TEST_F(SlamerLocalizerReplay, GlobalFlagFindsTheRobotWithoutItsStartPose) {
  const std::string out = kBinary + "/loc_global.lcm";
  std::string err;
  ASSERT_EQ(run("slamer-localizer",
                {"--config", config(), "--mode", "lfm", "--seed", "4", "--global", "--initial-pose", "3.5", "1.0",
                 "2.0", "--replay", recognized(), "--out", out},
                &err),
            0)
      << err;
  EXPECT_NE(err.find("global localization from the start"), std::string::npos) << err;
  test::ChildProcess eval(test::binary_path("slamer-eval"),
                          {"--world", kSource + "/config/worlds/small_room.yaml", "--json", out});
  ASSERT_EQ(eval.wait(60.0), std::optional<int>(0)) << eval.stderr_text();
  const nlohmann::json pose = nlohmann::json::parse(eval.stdout_text()).at("runs").at(0).at("pose");
  EXPECT_EQ(pose.at("lost_fraction").get<double>(), 0.0) << pose.dump();  // measured: max 0.45 m, mean 0.10
  EXPECT_LT(pose.at("position_mean_m").get<double>(), 0.2) << pose.dump();
}

TEST_F(SlamerLocalizerReplay, ReadsADamagedLogAroundTheDamageAndSaysSoInOneLine) {
  const std::string damaged = kBinary + "/loc_damaged.lcm";
  const std::string damaged_out = kBinary + "/loc_damaged_out.lcm";
  std::string bytes = test::read_file(recognized());
  // From an event's start, so the damage hits headers, not only one event's data.
  const std::size_t event_start = bytes.find("\xED\xA1\xDA\x01", bytes.size() / 2);
  ASSERT_NE(event_start, std::string::npos);
  std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(event_start), 3000, '\0');
  std::ofstream(damaged, std::ios::binary) << bytes;
  std::string err;
  ASSERT_EQ(localize(damaged, damaged_out, &err), 0) << err;
  EXPECT_NE(err.find("WARN " + damaged + ": skipped "), std::string::npos) << err;
  EXPECT_NE(err.find(" damaged bytes in 1 place(s)\n"), std::string::npos) << err;
  const auto damaged_counts = channel_counts(damaged_out);
  EXPECT_GE(damaged_counts.at("POSE"), channel_counts(output()).at("LIDAR") - 3);  // 3000 bytes: a few events
  EXPECT_EQ(damaged_counts.at("POSE"), damaged_counts.at("LIDAR"));
  std::remove(damaged.c_str());
  std::remove(damaged_out.c_str());
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

// The issue 11 case: the map calls no_entry_line something else, so class_map's
// entry would get no map prior; the localizer stops at start-up, naming the key.
TEST(SlamerLocalizer, AClassMapEntryTheMapLacksStopsItWithOneLine) {
  const std::string dir = kSource + "/config/maps/small_room/";
  const std::string map = kBinary + "/loc_renamed_map.yaml";
  std::ofstream(map) << "image: " << dir << "map.pgm\nresolution: 0.05\norigin: [-0.5, -0.5, 0.0]\n"
                     << "semantic:\n  image: " << dir << "semantic.png\n  classes:\n"
                     << "    - {name: door, color: [255, 0, 255]}\n    - {name: glass_door, color: [0, 255, 255]}\n"
                     << "    - {name: fence, color: [255, 128, 0]}\n    - {name: no_go, color: [255, 0, 0]}\n"
                     << "    - {name: others, color: [0, 0, 0]}\n";
  std::string err;
  EXPECT_EQ(run("slamer-localizer",
                {"--config", kSource + "/config/localizer.yaml", "--map", map, "--replay", "x", "--out", "y"}, &err),
            1);
  EXPECT_EQ(err,
            "slamer-localizer: config error: key 'localizer.slamer.class_map.no_entry_line': 'no_entry_line' is not "
            "a class of the map (it has: door, glass_door, fence, no_go, others); name one of them, or '' for free "
            "space\n");
  // LFM uses no classes: the same map and config start (and stop at the missing log).
  EXPECT_EQ(run("slamer-localizer",
                {"--config", kSource + "/config/localizer.yaml", "--map", map, "--mode", "lfm", "--replay",
                 kBinary + "/loc_no_such.lcm", "--out", kBinary + "/loc_x.lcm"},
                &err),
            1);
  EXPECT_EQ(err.find("class_map"), std::string::npos) << err;
  std::remove(map.c_str());
}

TEST(SlamerLocalizer, ReplayOfWhatIsNotALogExitsOneWithOneLine) {
  const std::string map = kSource + "/config/maps/small_room/map.yaml";
  const std::string empty = kBinary + "/loc_empty.lcm";
  { std::ofstream(empty, std::ios::binary); }
  std::string err;
  EXPECT_EQ(run("slamer-localizer", {"--map", map, "--replay", empty, "--out", kBinary + "/loc_x.lcm"}, &err), 1);
  EXPECT_NE(err.find("slamer-localizer: error: " + empty + " is empty: no events to replay\n"), std::string::npos)
      << err;
  EXPECT_EQ(run("slamer-localizer", {"--map", map, "--replay", kBinary, "--out", kBinary + "/loc_x.lcm"}, &err), 1);
  EXPECT_NE(err.find("slamer-localizer: error: " + kBinary + " is a folder, not an LCM log\n"), std::string::npos)
      << err;
  std::remove(empty.c_str());
  std::remove((kBinary + "/loc_x.lcm").c_str());
}

}  // namespace
}  // namespace slamer

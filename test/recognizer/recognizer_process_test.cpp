// slamer-recognizer as a program: offline replay is deterministic and copies
// every channel; live, it recognizes scans played by the real lcm-logplayer,
// recorded by the real lcm-logger, and shrugs off garbage.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <thread>

#include "common/process/decode.hpp"
#include "slamer/channel_stats_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBinary = SLAMER_BINARY_DIR;

// A short simulated log of the small world (8 s, 320 scans).
std::string short_log(const std::string& name) {
  const std::string config = kBinary + "/" + name + "_sim.yaml";
  std::ofstream(config) << "sim: {max_duration: 8.0}\n";
  const std::string log = kBinary + "/" + name + ".lcm";
  test::ChildProcess sim(test::binary_path("slamer-sim"), {"--world", kSource + "/config/worlds/small_room.yaml",
                                                           "--config", config, "--seed", "9", "--out", log});
  EXPECT_EQ(sim.wait(60.0), std::optional<int>(0)) << sim.stderr_text();
  return log;
}

// Waits until the log lcm-logger is writing holds an event on `channel` (the logger
// records and the sender is up, however long a loaded machine took to start them).
bool until_recorded(const std::string& path, const std::string& channel, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (std::filesystem::exists(path)) {
      lcm::LogFile log(path, "r");
      for (const lcm::LogEvent* e = log.good() ? log.readNextEvent() : nullptr; e != nullptr; e = log.readNextEvent()) {
        if (e->channel == channel) {
          return true;
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

std::map<std::string, std::vector<int64_t>> utimes_by_channel(const std::string& path) {
  lcm::LogFile log(path, "r");
  std::map<std::string, std::vector<int64_t>> result;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    // utime is the first field after the 8-byte fingerprint in every slamer message.
    int64_t utime = 0;
    if (e->datalen >= 16) {
      const auto* b = static_cast<const uint8_t*>(e->data) + 8;
      for (int i = 0; i < 8; ++i) {
        utime = (utime << 8) | b[i];
      }
    }
    result[e->channel].push_back(utime);
  }
  return result;
}

// LIDAR drops in the last PROCESS_STATUS of slamer-recognizer in a log, -1 if none.
// The message of the recognizer's last PROCESS_STATUS in a log.
std::string recognizer_status_message(const std::string& path) {
  std::string message;
  lcm::LogFile log(path, "r");
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    process_status_t status{};
    if (e->channel == "PROCESS_STATUS" &&
        decode_message(e->data, static_cast<std::size_t>(e->datalen), &status) == DecodeStatus::kOk &&
        status.process == "slamer-recognizer") {
      message = status.message;
    }
  }
  return message;
}

int64_t recognizer_drops(const std::string& path) {
  int64_t dropped = -1;
  lcm::LogFile log(path, "r");
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    process_status_t status{};
    if (e->channel == "PROCESS_STATUS" &&
        decode_message(e->data, static_cast<std::size_t>(e->datalen), &status) == DecodeStatus::kOk &&
        status.process == "slamer-recognizer") {
      for (const channel_stats_t& c : status.channels) {
        if (c.channel == "LIDAR" && c.direction == channel_stats_t::SUBSCRIBED) {
          dropped = c.drops;
        }
      }
    }
  }
  return dropped;
}

TEST(SlamerRecognizer, ReplayIsDeterministicAndCopiesEveryChannel) {
  const std::string in = short_log("rec_replay");
  const std::string a = kBinary + "/rec_replay_a.lcm";
  const std::string b = kBinary + "/rec_replay_b.lcm";
  for (const std::string& out : {a, b}) {
    test::ChildProcess rec(test::binary_path("slamer-recognizer"),
                           {"--config", kSource + "/config/recognizer.yaml", "--replay", in, "--out", out});
    ASSERT_EQ(rec.wait(120.0), std::optional<int>(0)) << rec.stderr_text();
  }
  EXPECT_TRUE(test::read_file(a) == test::read_file(b)) << "two replays differ";
  const auto input = utimes_by_channel(in);
  const auto output = utimes_by_channel(a);
  for (const auto& [channel, utimes] : input) {
    if (channel != "PROCESS_STATUS") {  // there the recognizer's own go in too
      EXPECT_EQ(output.at(channel), utimes) << channel << " not copied through unchanged";
    }
  }
  int64_t own_statuses = 0;
  lcm::LogFile out_log(a, "r");
  for (const lcm::LogEvent* e = out_log.readNextEvent(); e != nullptr; e = out_log.readNextEvent()) {
    process_status_t status{};
    own_statuses += e->channel == "PROCESS_STATUS" &&
                    decode_message(e->data, static_cast<std::size_t>(e->datalen), &status) == DecodeStatus::kOk &&
                    status.process == "slamer-recognizer";
  }
  EXPECT_GE(own_statuses, 9);  // the replay's PROCESS_STATUS: 8 s of log, one a second
  EXPECT_EQ(output.at("PROCESS_STATUS").size(),
            (input.count("PROCESS_STATUS") ? input.at("PROCESS_STATUS").size() : 0u) + own_statuses);
  EXPECT_EQ(output.at("LINE_OBJECTS"), input.at("LIDAR"));  // one result per scan, with its utime
  test::ChildProcess same(test::binary_path("slamer-recognizer"), {"--replay", in, "--out", in});
  EXPECT_EQ(same.wait(10.0), std::optional<int>(1));
  EXPECT_NE(same.stderr_text().find("must not be the input log"), std::string::npos) << same.stderr_text();
  for (const std::string& f : {in, a, b}) {
    std::remove(f.c_str());
  }
}

TEST(SlamerRecognizer, LiveWithTheRealLogplayerAndLogger) {
  const std::string in = short_log("rec_live");
  const std::string recorded = kBinary + "/rec_live_recorded.lcm";
  std::remove(recorded.c_str());
  const std::string url = test::unique_lcm_url(11);
  test::ChildProcess logger("/usr/bin/lcm-logger", {"--lcm-url=" + url, "-f", "-q", recorded});
  test::ChildProcess recognizer(test::binary_path("slamer-recognizer"),
                                {"--config", kSource + "/config/recognizer.yaml", "--lcm-url", url});
  // Garbage first: it must be counted, not fatal. Sent once the recognizer is up (its first
  // PROCESS_STATUS is recorded), or nothing would be there to count it.
  ASSERT_TRUE(until_recorded(recorded, "PROCESS_STATUS", 30.0)) << recognizer.stderr_text();
  {
    lcm::LCM bus(url);
    ASSERT_TRUE(bus.good());
    const std::string junk = "definitely not a laser scan";
    bus.publish("LIDAR", junk.data(), static_cast<unsigned>(junk.size()));
  }
  test::ChildProcess player("/usr/bin/lcm-logplayer", {"--lcm-url=" + url, "-s", "2", "-e", "^LIDAR$", in});
  ASSERT_TRUE(player.wait(60.0).has_value());
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  recognizer.signal(SIGINT);
  EXPECT_EQ(recognizer.wait(5.0), std::optional<int>(0)) << recognizer.stderr_text();
  logger.signal(SIGINT);
  ASSERT_TRUE(logger.wait(5.0).has_value());
  EXPECT_NE(recognizer.stderr_text().find("decode error"), std::string::npos) << recognizer.stderr_text();

  const auto played = utimes_by_channel(in).at("LIDAR");
  const auto got = utimes_by_channel(recorded);
  ASSERT_TRUE(got.count("LINE_OBJECTS") != 0) << "nothing recognized; stderr:\n" << recognizer.stderr_text();
  const std::set<int64_t> scan_times(played.begin(), played.end());
  for (const int64_t utime : got.at("LINE_OBJECTS")) {
    ASSERT_TRUE(scan_times.count(utime) != 0) << "LINE_OBJECTS with a utime no scan had: " << utime;
  }
  // How many get through depends on the build's speed (a sanitizer build
  // loses most to the kernel's buffer); what holds in every build: nothing is
  // invented, and what was missed and noticed is counted, never more.
  const int64_t dropped = recognizer_drops(recorded);
  ASSERT_GE(dropped, 0) << "no PROCESS_STATUS of slamer-recognizer was recorded";
  const auto recognized = static_cast<int64_t>(got.at("LINE_OBJECTS").size());
  EXPECT_GE(recognized, 1);
  EXPECT_LE(recognized + dropped, static_cast<int64_t>(played.size()))
      << recognized << " recognized, " << dropped << " counted as dropped, " << played.size() << " played";
  for (const std::string& f : {in, recorded}) {
    std::remove(f.c_str());
  }
}

// Scans sent slowly with seq gaps, a repeat and an older one: each accepted
// scan gives one LINE_OBJECTS, each rejected one is one drop, and the scans
// the seq gap says never arrived are reported as missed, not as drops.
TEST(SlamerRecognizer, CountsMissedAndOutOfOrderScans) {
  const std::string url = test::unique_lcm_url(12);
  const std::string recorded = kBinary + "/rec_drops_recorded.lcm";
  std::remove(recorded.c_str());
  test::ChildProcess logger("/usr/bin/lcm-logger", {"--lcm-url=" + url, "-f", "-q", recorded});
  test::ChildProcess recognizer(test::binary_path("slamer-recognizer"), {"--lcm-url", url});
  lcm::LCM bus(url);
  ASSERT_TRUE(bus.good());
  ASSERT_TRUE(until_recorded(recorded, "PROCESS_STATUS", 30.0)) << recognizer.stderr_text();
  const auto send = [&](int64_t seq, int64_t utime) {
    laser_scan_t scan{};
    scan.utime = utime;
    scan.seq = seq;
    scan.frame = "laser";
    scan.angle_min = -2.0;
    scan.angle_increment = 0.01;
    scan.range_min = 0.1f;
    scan.range_max = 30.0f;
    scan.ranges.assign(400, 3.0f);
    scan.nranges = 400;
    std::vector<uint8_t> bytes(static_cast<std::size_t>(scan.getEncodedSize()));
    scan.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    bus.publish("LIDAR", bytes.data(), static_cast<unsigned>(bytes.size()));
    std::this_thread::sleep_for(std::chrono::milliseconds(600));  // slow enough for any build
  };
  const int64_t t0 = 1'700'000'000'000'000;
  send(0, t0);
  send(1, t0 + 25'000);
  send(4, t0 + 100'000);  // seq 2 and 3 never arrived: 2 missed
  send(4, t0 + 100'000);  // the same scan again: 1 drop
  send(3, t0 + 75'000);   // older than the last: 1 drop
  send(5, t0 + 125'000);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // a PROCESS_STATUS goes out meanwhile
  recognizer.signal(SIGINT);
  EXPECT_EQ(recognizer.wait(10.0), std::optional<int>(0)) << recognizer.stderr_text();
  logger.signal(SIGINT);
  ASSERT_TRUE(logger.wait(5.0).has_value());
  const auto got = utimes_by_channel(recorded);
  ASSERT_TRUE(got.count("LINE_OBJECTS") != 0) << recognizer.stderr_text();
  EXPECT_EQ(got.at("LINE_OBJECTS"), (std::vector<int64_t>{t0, t0 + 25'000, t0 + 100'000, t0 + 125'000}));
  EXPECT_EQ(recognizer_drops(recorded), 2);
  EXPECT_EQ(recognizer_status_message(recorded), "2 scans missed (gaps in seq)");
  std::remove(recorded.c_str());
}

}  // namespace
}  // namespace slamer

// The bus (bus.hpp) on its in-memory and log transports: decoding and
// counting, handler faults, timers in bus time, PROCESS_STATUS, replay order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "common/process/event_log.hpp"
#include "common/process/log_bus.hpp"
#include "common/process/memory_bus.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/process_status_t.hpp"

namespace slamer {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

odometry_t odometry(int64_t utime, double x) {
  odometry_t m{};
  m.utime = utime;
  m.x = x;
  return m;
}

std::vector<uint8_t> encode(const odometry_t& m) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

const channel_stats_t* find_channel(const process_status_t& status, const std::string& channel, int8_t direction) {
  for (const channel_stats_t& c : status.channels) {
    if (c.channel == channel && c.direction == direction) {
      return &c;
    }
  }
  return nullptr;
}

TEST(MemoryBus, DeliversDecodedMessagesAndCountsGarbagePerChannel) {
  MemoryBus bus("slamer-test", kT0);
  std::vector<double> xs;
  std::vector<int64_t> arrivals;
  bus.subscribe<odometry_t>("ODOMETRY", [&](const odometry_t& m, const ReceiveInfo& info) {
    xs.push_back(m.x);
    arrivals.push_back(info.receive_utime);
  });
  bus.inject("ODOMETRY", odometry(kT0, 1.5), kT0 + 10);
  bus.inject("ODOMETRY", std::vector<uint8_t>{1, 2, 3}, kT0 + 20);   // too short
  bus.inject("ODOMETRY", std::vector<uint8_t>(40, 0xAB), kT0 + 30);  // wrong type
  std::vector<uint8_t> truncated = encode(odometry(kT0, 2.0));
  truncated.resize(truncated.size() - 3);
  bus.inject("ODOMETRY", truncated, kT0 + 40);
  bus.inject("ODOMETRY", odometry(kT0 + 50, 2.5), kT0 + 50);
  bus.run_until(kT0 + 100);
  EXPECT_EQ(xs, (std::vector<double>{1.5, 2.5}));
  EXPECT_EQ(arrivals, (std::vector<int64_t>{kT0 + 10, kT0 + 50}));
  const process_status_t status = bus.health().status(bus.now());
  const channel_stats_t* in = find_channel(status, "ODOMETRY", channel_stats_t::SUBSCRIBED);
  ASSERT_NE(in, nullptr);
  EXPECT_EQ(in->messages, 2);
  EXPECT_EQ(in->decode_errors, 3);
}

TEST(MemoryBus, AHandlerThatThrowsIsCountedAndTheBusGoesOn) {
  MemoryBus bus("slamer-test", kT0);
  int handled = 0;
  bus.subscribe<odometry_t>("ODOMETRY", [&](const odometry_t& m, const ReceiveInfo&) {
    ++handled;
    if (m.x < 0) {
      throw std::runtime_error("negative x");
    }
  });
  bus.inject("ODOMETRY", odometry(kT0, -1.0), kT0 + 1);
  bus.inject("ODOMETRY", odometry(kT0, 1.0), kT0 + 2);
  EXPECT_NO_THROW(bus.run_until(kT0 + 10));
  EXPECT_EQ(handled, 2);
  const std::string summary = bus.health().take_error_summary();
  EXPECT_NE(summary.find("1 handler error"), std::string::npos) << summary;
  EXPECT_NE(summary.find("negative x"), std::string::npos) << summary;
}

TEST(MemoryBus, TimersFireInBusTimeAndStatusGoesOutEachPeriod) {
  ProcessOptions options;
  options.status_period = 0.5;
  MemoryBus bus("slamer-test", kT0, options);
  std::vector<int64_t> fired;
  bus.every(0.1, [&] { fired.push_back(bus.now() - kT0); });
  bus.advertise("POSE");
  bus.run_until(kT0 + 350'000);
  EXPECT_EQ(fired, (std::vector<int64_t>{100'000, 200'000, 300'000}));
  bus.run_until(kT0 + 1'000'000);
  EXPECT_EQ(fired.size(), 10u);
  const auto statuses = bus.published_on<process_status_t>("PROCESS_STATUS");
  // One at the start, then every 0.5 s.
  ASSERT_EQ(statuses.size(), 3u);
  EXPECT_EQ(statuses[0].utime, kT0);
  EXPECT_EQ(statuses[2].utime, kT0 + 1'000'000);
  EXPECT_EQ(statuses[2].pid, 0);  // deterministic outside live runs
  EXPECT_NE(find_channel(statuses[0], "POSE", channel_stats_t::PUBLISHED), nullptr) << "advertised from the start";
}

TEST(MemoryBus, FinishRunsTheCallbacksBeforeTheLastStatus) {
  MemoryBus bus("slamer-test", kT0);
  bus.advertise("DONE");
  bus.at_finish([&] { bus.publish("DONE", odometry(bus.now(), 7.0)); });
  bus.inject("ODOMETRY", odometry(kT0, 1.0), kT0 + 2'500'000);
  bus.subscribe<odometry_t>("ODOMETRY", [](const odometry_t&, const ReceiveInfo&) {});
  EXPECT_EQ(bus.run(), 0);
  ASSERT_GE(bus.published().size(), 2u);
  EXPECT_EQ(bus.published()[bus.published().size() - 2].channel, "DONE");
  EXPECT_EQ(bus.published().back().channel, "PROCESS_STATUS");
  EXPECT_EQ(bus.published().back().utime, kT0 + 2'500'000);
}

struct Event {
  std::string channel;
  int64_t timestamp;
  std::vector<uint8_t> data;
};

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

void write_events(const std::string& path, const std::vector<Event>& events) {
  lcm::LogFile log(path, "w");
  ASSERT_TRUE(log.good());
  for (const Event& e : events) {
    lcm::LogEvent event;
    event.timestamp = e.timestamp;
    event.channel = e.channel;
    event.datalen = static_cast<int32_t>(e.data.size());
    event.data = const_cast<uint8_t*>(e.data.data());
    ASSERT_EQ(log.writeEvent(&event), 0);
  }
}

std::vector<Event> read_events(const std::string& path) {
  std::vector<Event> events;
  EventLogReader reader(path);
  while (const std::optional<LogEvent> e = reader.next()) {
    events.push_back({e->channel, e->timestamp, e->data});
  }
  return events;
}

// A program on the replay bus: doubles each ODOMETRY x onto DOUBLED and counts timer ticks.
void replay_doubler(const std::string& in, const std::string& out, std::vector<int64_t>* ticks) {
  LogBus bus("slamer-doubler", in, out, ProcessOptions{});
  bus.advertise("DOUBLED");
  bus.subscribe<odometry_t>(
      "ODOMETRY", [&](const odometry_t& m, const ReceiveInfo&) { bus.publish("DOUBLED", odometry(m.utime, 2 * m.x)); });
  bus.every(0.25, [&] { ticks->push_back(bus.now()); });
  ASSERT_EQ(bus.run(), 0);
}

TEST(LogBus, ReplayCopiesInputWritesOutputsAfterTheirCauseAndLeavesOutOldOutputs) {
  const std::string in = temp_path("bus_test_in.lcm");
  const std::string out = temp_path("bus_test_out.lcm");
  process_status_t old_status{};
  old_status.process = "slamer-doubler";  // an earlier run's own status: left out
  old_status.message = "";
  process_status_t other_status{};
  other_status.process = "slamer-other";  // another process's: copied
  other_status.message = "";
  const auto bytes_of = [](const auto& m) {
    std::vector<uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
    m.encode(b.data(), 0, static_cast<int>(b.size()));
    return b;
  };
  write_events(in, {{"ODOMETRY", kT0, encode(odometry(kT0, 1.0))},
                    {"DOUBLED", kT0 + 1, encode(odometry(kT0, 99.0))},  // an earlier run's output
                    {"OTHER", kT0 + 2, {1, 2, 3}},
                    {"PROCESS_STATUS", kT0 + 3, bytes_of(old_status)},
                    {"PROCESS_STATUS", kT0 + 4, bytes_of(other_status)},
                    {"ODOMETRY", kT0 + 600'000, encode(odometry(kT0 + 600'000, 3.0))}});
  std::vector<int64_t> ticks;
  replay_doubler(in, out, &ticks);
  EXPECT_EQ(ticks, (std::vector<int64_t>{kT0 + 250'000, kT0 + 500'000}));  // in log time
  std::vector<std::string> channels;
  std::vector<Event> doubled;
  for (const Event& e : read_events(out)) {
    channels.push_back(e.channel);
    if (e.channel == "DOUBLED") {
      doubled.push_back(e);
    }
  }
  EXPECT_EQ(channels, (std::vector<std::string>{"PROCESS_STATUS", "ODOMETRY", "DOUBLED", "OTHER", "PROCESS_STATUS",
                                                "ODOMETRY", "DOUBLED", "PROCESS_STATUS"}));
  ASSERT_EQ(doubled.size(), 2u);
  EXPECT_EQ(doubled[0].timestamp, kT0);
  EXPECT_EQ(doubled[1].timestamp, kT0 + 600'000);
  odometry_t second{};
  ASSERT_EQ(decode_message(doubled[1].data.data(), doubled[1].data.size(), &second), DecodeStatus::kOk);
  EXPECT_DOUBLE_EQ(second.x, 6.0);
  // Deterministic: the same input gives the same bytes.
  const std::string again = temp_path("bus_test_again.lcm");
  replay_doubler(in, again, &ticks);
  EXPECT_EQ(read_events(out).size(), read_events(again).size());
  std::ifstream a(out, std::ios::binary), b(again, std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b)));
  for (const std::string& f : {in, out, again}) {
    std::remove(f.c_str());
  }
}

TEST(LogBus, TimeGoingBackByMoreThanASecondRestartsTheTimersThere) {
  const std::string in = temp_path("bus_test_back.lcm");
  const std::string out = temp_path("bus_test_back_out.lcm");
  write_events(in, {{"ODOMETRY", kT0 + 10'000'000, encode(odometry(kT0, 1.0))},
                    {"ODOMETRY", kT0 + 10'600'000, encode(odometry(kT0, 1.0))},
                    {"ODOMETRY", kT0 + 10'550'000, encode(odometry(kT0, 1.0))},  // jitter: the clock stays
                    {"ODOMETRY", kT0, encode(odometry(kT0, 1.0))},               // the log again
                    {"ODOMETRY", kT0 + 300'000, encode(odometry(kT0, 1.0))}});
  std::vector<int64_t> ticks;
  replay_doubler(in, out, &ticks);
  EXPECT_EQ(ticks, (std::vector<int64_t>{kT0 + 10'250'000, kT0 + 10'500'000, kT0 + 250'000}));
  std::remove(in.c_str());
  std::remove(out.c_str());
}

TEST(LogBus, WhatIsNotALogIsOneLineError) {
  const std::string out = temp_path("bus_test_bad_out.lcm");
  const std::string empty = temp_path("bus_test_empty.lcm");
  const std::string text = temp_path("bus_test_text.lcm");
  { std::ofstream(empty, std::ios::binary); }
  { std::ofstream(text) << "this is not an LCM log, just some text that goes on for a while\n"; }
  const auto message = [&](const std::string& in) -> std::string {
    try {
      LogBus bus("slamer-test", in, out, ProcessOptions{});
      bus.run();
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message(empty), empty + " is empty: no events to replay");
  EXPECT_EQ(message(text), text + " is not an LCM log (no event in it)");
  EXPECT_EQ(message(temp_path("bus_test_missing.lcm")), "no such log: " + temp_path("bus_test_missing.lcm"));
  EXPECT_EQ(message(std::filesystem::temp_directory_path().string()),
            std::filesystem::temp_directory_path().string() + " is a folder, not an LCM log");
  EXPECT_EQ(message(empty).find('\n'), std::string::npos);
  for (const std::string& f : {out, empty, text}) {
    std::remove(f.c_str());
  }
}

TEST(LogBus, RecorderRunsTimersInVirtualTimeUntilStopped) {
  const std::string out = temp_path("bus_test_record.lcm");
  {
    LogBus bus("slamer-recorder", out, kT0, ProcessOptions{});
    bus.advertise("ODOMETRY");
    int steps = 0;
    bus.every(0.005, [&] {
      bus.publish("ODOMETRY", odometry(bus.now(), steps), bus.now() + 1000);
      if (++steps == 400) {
        bus.stop();
      }
    });
    ASSERT_EQ(bus.run(), 0);
  }
  int64_t odometry_events = 0;
  int64_t last = 0;
  for (const Event& e : read_events(out)) {
    if (e.channel == "ODOMETRY") {
      ++odometry_events;
      last = e.timestamp;
    }
  }
  EXPECT_EQ(odometry_events, 400);
  EXPECT_EQ(last, kT0 + 400 * 5000 + 1000);  // the event time asked for, in virtual time
  std::remove(out.c_str());
}

}  // namespace
}  // namespace slamer

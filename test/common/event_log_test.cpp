// EventLogReader against logs written by LCM's own writer, then damaged the
// ways real logs get damaged.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>

#include "common/process/event_log.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

struct WrittenLog {
  std::string path;
  std::vector<LogEvent> events;
  std::vector<std::size_t> offsets;  // where each event starts in the file
};

// 50 events on 3 channels written by lcm::LogFile; the data holds sync words too.
WrittenLog write_log(const std::string& name) {
  WrittenLog log;
  log.path = (std::filesystem::temp_directory_path() / name).string();
  lcm::LogFile file(log.path, "w");
  std::size_t offset = 0;
  for (int i = 0; i < 50; ++i) {
    LogEvent e;
    e.timestamp = 1'700'000'000'000'000 + 25'000 * i;
    e.channel = i % 3 == 0 ? "LIDAR" : i % 3 == 1 ? "ODOMETRY" : "LINE_OBJECTS";
    e.data.assign(static_cast<std::size_t>(40 + 13 * i), static_cast<uint8_t>(i));
    const uint8_t sync[4] = {0xED, 0xA1, 0xDA, 0x01};
    std::copy(std::begin(sync), std::end(sync), e.data.begin() + 8);
    lcm::LogEvent out;
    out.timestamp = e.timestamp;
    out.channel = e.channel;
    out.datalen = static_cast<int32_t>(e.data.size());
    out.data = e.data.data();
    EXPECT_EQ(file.writeEvent(&out), 0);
    log.offsets.push_back(offset);
    offset += kLogEventHeaderBytes + e.channel.size() + e.data.size();
    log.events.push_back(std::move(e));
  }
  return log;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::vector<LogEvent> read_all(EventLogReader* reader) {
  std::vector<LogEvent> events;
  while (std::optional<LogEvent> e = reader->next()) {
    events.push_back(std::move(*e));
  }
  return events;
}

void expect_same(const LogEvent& got, const LogEvent& want) {
  EXPECT_EQ(got.timestamp, want.timestamp);
  EXPECT_EQ(got.channel, want.channel);
  EXPECT_EQ(got.data, want.data);
}

TEST(EventLogReader, ReadsWhatLcmWroteExactly) {
  const WrittenLog log = write_log("slamer_event_log_intact.lcm");
  EventLogReader reader(log.path);
  const std::vector<LogEvent> events = read_all(&reader);
  ASSERT_EQ(events.size(), log.events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    expect_same(events[i], log.events[i]);
    EXPECT_EQ(events[i].event_number, static_cast<int64_t>(i));
  }
  EXPECT_EQ(reader.problems(), "");
  EXPECT_DOUBLE_EQ(reader.fraction_read(), 1.0);
  std::filesystem::remove(log.path);
}

TEST(EventLogReader, SkipsADamagedStretchAndReadsOn) {
  const WrittenLog log = write_log("slamer_event_log_damaged.lcm");
  std::string bytes = test::read_file(log.path);
  // Zero 30 bytes from the middle of event 20's header into its channel name.
  std::fill_n(bytes.begin() + static_cast<std::ptrdiff_t>(log.offsets[20] + 10), 30, '\0');
  // And a channel name longer than LCM's reader accepts (it asserts) in event 30's header.
  bytes[log.offsets[30] + 22] = 0x7f;
  write_file(log.path, bytes);
  EventLogReader reader(log.path);
  const std::vector<LogEvent> events = read_all(&reader);
  ASSERT_EQ(events.size(), log.events.size() - 2);
  for (std::size_t i = 0, k = 0; i < log.events.size(); ++i) {
    if (i != 20 && i != 30) {
      expect_same(events[k++], log.events[i]);
    }
  }
  EXPECT_EQ(reader.damaged_stretches(), 2);
  EXPECT_EQ(reader.damaged_bytes(),
            static_cast<int64_t>((log.offsets[21] - log.offsets[20]) + (log.offsets[31] - log.offsets[30])));
  EXPECT_FALSE(reader.truncated());
  EXPECT_EQ(reader.problems(),
            log.path + ": skipped " + std::to_string(reader.damaged_bytes()) + " damaged bytes in 2 place(s)");
  std::filesystem::remove(log.path);
}

TEST(EventLogReader, ALogCutOffWhileWrittenKeepsEveryWholeEvent) {
  const WrittenLog log = write_log("slamer_event_log_cut.lcm");
  const std::string bytes = test::read_file(log.path);
  for (const std::size_t cut : {log.offsets[40] + 3, log.offsets[40] + 20, log.offsets[40] + 100}) {
    write_file(log.path, bytes.substr(0, cut));
    EventLogReader reader(log.path);
    EXPECT_EQ(read_all(&reader).size(), 40u) << "cut at " << cut;
    EXPECT_TRUE(reader.truncated()) << "cut at " << cut;
    EXPECT_EQ(reader.damaged_bytes(), static_cast<int64_t>(cut - log.offsets[40]));
    EXPECT_NE(reader.problems().find("ends inside an event"), std::string::npos) << reader.problems();
  }
  std::filesystem::remove(log.path);
}

TEST(EventLogReader, NotALogAtAllIsReportedNotTrusted) {
  const std::string path = (std::filesystem::temp_directory_path() / "slamer_event_log_text.lcm").string();
  write_file(path, std::string(5000, 'x'));
  EventLogReader text(path);
  EXPECT_TRUE(read_all(&text).empty());
  EXPECT_EQ(text.problems(), path + ": skipped 5000 damaged bytes in 1 place(s)");
  write_file(path, "");
  EventLogReader empty(path);
  EXPECT_TRUE(read_all(&empty).empty());
  EXPECT_EQ(empty.problems(), "");
  std::filesystem::remove(path);
  try {
    EventLogReader missing(path);
    ADD_FAILURE() << "opened a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read log " + path + ": No such file or directory");
  }
}

}  // namespace
}  // namespace slamer

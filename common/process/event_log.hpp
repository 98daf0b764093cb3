// Reads LCM log files (the format lcm-logger writes: per event the sync word
// 0xEDA1DA01, int64 event number, int64 timestamp [us], int32 channel length,
// int32 data length, channel, data; big-endian) without trusting them. LCM's
// own reader stops for good at the first damaged event (and asserts on a long
// channel name); this one checks every header, skips a damaged stretch to the
// next event that parses, and says what it skipped and whether the file ends
// inside an event (a logger killed mid-write).
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace slamer {

struct LogEvent {
  int64_t event_number = 0;
  int64_t timestamp = 0;  // [us]
  std::string channel;
  std::vector<uint8_t> data;
};

enum class EventParse { kEvent, kIncomplete, kDamaged };

inline constexpr std::size_t kLogEventHeaderBytes = 28;
inline constexpr std::size_t kMaxLogChannelLength = 255;
inline constexpr std::size_t kMaxLogEventBytes = 256u << 20;

// Parses the event at the start of `bytes`: kEvent (with *used its size),
// kIncomplete (more bytes could make it one), or kDamaged (it never will).
EventParse parse_log_event(std::span<const uint8_t> bytes, LogEvent* event, std::size_t* used);

class EventLogReader {
 public:
  // Throws std::runtime_error (one line) if the file cannot be opened.
  explicit EventLogReader(const std::string& path);
  // Reads an open stream (e.g. fmemopen), which it closes; `name` is for problems().
  EventLogReader(std::FILE* file, std::string name);
  ~EventLogReader();
  EventLogReader(const EventLogReader&) = delete;
  EventLogReader& operator=(const EventLogReader&) = delete;

  // The next intact event; nullopt at the end of the file.
  std::optional<LogEvent> next();

  double fraction_read() const;
  int64_t damaged_bytes() const { return damaged_bytes_; }  // skipped as not part of any intact event
  int64_t damaged_stretches() const { return damaged_stretches_; }
  bool truncated() const { return truncated_; }  // the file ends inside an event
  // "" for an intact log, else one line saying what was skipped.
  std::string problems() const;

 private:
  bool fill(std::size_t wanted);  // false at the end of the file

  std::string path_;
  std::FILE* file_ = nullptr;
  double size_ = 1.0;
  std::vector<uint8_t> buffer_;
  std::size_t start_ = 0;  // first unread byte in buffer_
  int64_t consumed_ = 0;   // bytes of the file before buffer_[start_]
  int64_t damaged_bytes_ = 0;
  int64_t damaged_stretches_ = 0;
  bool in_damage_ = false;
  bool truncated_ = false;
};

}  // namespace slamer

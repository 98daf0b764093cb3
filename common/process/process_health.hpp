// What a process knows about its own health: per-channel message, decode-error
// and drop counters, its state, and its processing time. Turned into a
// PROCESS_STATUS message once a second by the process loop. No clock or I/O
// here: times are passed in.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/process/decode.hpp"
#include "common/stats/rolling_percentiles.hpp"
#include "slamer/process_status_t.hpp"

namespace slamer {

class ProcessHealth {
 public:
  ProcessHealth(std::string process_name, int32_t pid, int64_t start_utime);

  void add_channel(const std::string& channel, int8_t direction);
  void count_message(const std::string& channel, int8_t direction, int64_t utime);
  void count_decode_error(const std::string& channel, DecodeStatus status, int64_t utime);
  void count_drop(const std::string& channel, int8_t direction, int64_t count = 1);
  // Drops a library counts itself (e.g. stale scans in a node): read when the
  // status is made and added to the channel's drops, so they are kept in one place.
  void add_drop_source(const std::string& channel, int8_t direction, std::function<int64_t()> drops);
  void count_handler_error(const std::string& what);
  void record_processing_time(double seconds);
  void set_state(int8_t state, std::string message);

  // A moment's problem (a driver restarted, a stream's gap): the next status
  // to publish says it, at `state` or worse, whatever the state is by then.
  void note_event(int8_t state, std::string message);

  int8_t state() const { return state_; }
  process_status_t status(int64_t now_utime) const;
  // status() with the events noted since the last call: the status to publish.
  process_status_t take_status(int64_t now_utime);

  // One line summarizing the decode and handler errors since the last call
  // ("3 decode errors: LIDAR 2 (wrong fingerprint), ODOMETRY 1 (truncated or
  // malformed)"), or an empty string if there were none.
  std::string take_error_summary();

 private:
  struct ChannelCounters {
    int64_t messages = 0;
    int64_t decode_errors = 0;
    int64_t drops = 0;
    int64_t last_utime = 0;
    int64_t unreported_errors = 0;
    DecodeStatus last_error = DecodeStatus::kOk;
    std::vector<std::function<int64_t()>> drop_sources;
  };
  using ChannelKey = std::pair<std::string, int8_t>;

  std::string process_name_;
  int32_t pid_;
  int64_t start_utime_;
  int8_t state_ = process_status_t::OK;
  std::string message_;
  static constexpr std::size_t kEventsKept = 3;
  int8_t event_state_ = process_status_t::OK;
  std::vector<std::string> events_;  // since the last take_status(), up to kEventsKept
  int64_t events_more_ = 0;
  std::map<ChannelKey, ChannelCounters> channels_;
  RollingPercentiles processing_time_;
  int64_t unreported_handler_errors_ = 0;
  std::string last_handler_error_;
};

}  // namespace slamer

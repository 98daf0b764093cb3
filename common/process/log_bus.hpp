// The offline bus (bus.hpp): an LCM log in, an LCM log out, the log's
// timestamps as the clock. Each input event is copied to the output, then
// handed to the channel's handlers; what they publish is written right after
// it with its timestamp. Timers fire in log time, before the first event at
// or past their due time (so a 10 ms timer fires as it would have live).
// Left out of the output: events on the program's own advertised channels
// (an earlier run's outputs) and the PROCESS_STATUS of a process with the
// program's name. Damaged stretches of the input are skipped (event_log.hpp)
// and reported in one warning. Time going back in the input by more than a
// second (a log played twice) restarts the clock and the timers there; less
// is jitter, and the clock stays where it is.
//
// Without an input log it is a recorder: run() fires the timers in virtual
// time from `start_utime`, as fast as the CPU allows, until stop() (a
// simulator writing its log).
//
// The output depends only on the input: the PROCESS_STATUS written carries
// pid 0 and no processing times.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <optional>
#include <string>

#include "common/process/bus.hpp"
#include "common/process/event_log.hpp"

namespace slamer {

struct LogBusStats {
  int64_t events_in = 0;
  int64_t events_left_out = 0;  // earlier outputs of this program
  int64_t events_handled = 0;   // delivered to a handler
  int64_t events_out = 0;
};

class LogBus final : public Bus {
 public:
  // Replays `in_path` into `out_path`. Throws std::runtime_error (one line)
  // if the input is missing, not a log, empty, the same file as the output,
  // or the output cannot be written.
  LogBus(std::string name, const std::string& in_path, const std::string& out_path, ProcessOptions options);
  // Records into `out_path` with a virtual clock starting at `start_utime`.
  LogBus(std::string name, const std::string& out_path, int64_t start_utime, ProcessOptions options);
  ~LogBus() override;

  int64_t now() const override { return now_; }
  bool is_live() const override { return false; }
  int run() override;
  const LogBusStats& stats() const { return stats_; }

 private:
  void start_receiving(const std::string&) override {}
  bool send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) override;
  void write(const std::string& channel, const uint8_t* data, std::size_t size, int64_t timestamp);
  bool is_own_status(const LogEvent& event) const;
  void fire_timers_until(int64_t utime);

  std::string out_path_;
  std::string in_path_;
  std::unique_ptr<EventLogReader> in_;
  std::unique_ptr<lcm::LogFile> out_;
  int64_t now_ = 0;
  LogBusStats stats_;
};

}  // namespace slamer

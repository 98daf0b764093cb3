// The message bus every program is written against: one interface, three
// transports (the shape of Drake's DrakeLcmInterface with DrakeLcm,
// DrakeLcmLog and memq):
//   * LcmBus (lcm_bus.hpp): live LCM over UDP multicast; the host clock;
//     SIGINT/SIGTERM end run(); device file descriptors can be watched.
//   * LogBus (log_bus.hpp): offline; the log's timestamps are the clock,
//     timers fire in log time, publications go to the output log; as fast as
//     the CPU allows and deterministic.
//   * MemoryBus (memory_bus.hpp): in memory, for tests of a whole program's
//     wiring without sockets; the test drives the clock.
//
// A program subscribes typed handlers, advertises what it publishes, adds
// timers, and calls run(). Whatever the transport, the bus:
//   * decodes untrusted bytes (decode.hpp), counting failures per channel in
//     ProcessHealth and summarizing them in the log at most once per
//     error_log_period; handlers see decoded messages only;
//   * never lets a handler's or timer's exception escape (counted, logged);
//   * publishes PROCESS_STATUS every status_period of bus time (into the
//     output log on a LogBus), and once more when run() ends;
//   * runs the at_finish callbacks when run() ends (clean stop, end of log).
//
// Writing a new process: parse the command line with process_main(), load the
// config, `auto bus = open_bus(cli, "slamer-x", config.process)` (process_main.hpp),
// build the library objects, then `bus->subscribe<Msg>(channel, handler)`,
// `bus->advertise(channel)` for every output, `bus->every(period, callback)`
// for periodic work, and `return bus->run();`. Handlers convert messages to
// library types, call the library with bus->now() as the time, and publish.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/process/decode.hpp"
#include "common/process/process_health.hpp"
#include "common/process/process_options.hpp"
#include "slamer/channel_stats_t.hpp"

namespace slamer {

struct ReceiveInfo {
  std::string channel;
  int64_t receive_utime = 0;  // bus time the bytes arrived [us]
};

// The state's name for log lines: "OK", "DEGRADED", "ERROR".
const char* process_state_name(int8_t process_state);

class Bus {
 public:
  template <class Msg>
  using Handler = std::function<void(const Msg&, const ReceiveInfo&)>;
  using RawHandler = std::function<void(const uint8_t* data, std::size_t size, const ReceiveInfo&)>;

  virtual ~Bus() = default;
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  // Subscribes to exactly `channel` (not a pattern). With record_time, the
  // handler's run time goes into the processing-time p50/p99 of the status
  // (live only: a replay's status stays deterministic).
  template <class Msg>
  void subscribe(const std::string& channel, Handler<Msg> handler, bool record_time = false);
  void subscribe_raw(const std::string& channel, RawHandler handler, bool record_time = false);

  // Declares an output channel: listed in PROCESS_STATUS from the start, and a
  // LogBus leaves this channel's events of the input log out (an earlier
  // run's outputs).
  void advertise(const std::string& channel);

  // Returns false (and counts a drop) if the message could not be sent.
  // `event_utime` (optional) is when the message goes on the bus, if not
  // now(): a LogBus writes it as the event's timestamp; live buses ignore it.
  template <class Msg>
  bool publish(const std::string& channel, const Msg& msg, int64_t event_utime = kNow);
  bool publish_raw(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime = kNow);

  // Calls `callback` every `period_s` seconds of bus time from run().
  void every(double period_s, std::function<void()> callback);
  // Called once when run() ends, before the last PROCESS_STATUS.
  void at_finish(std::function<void()> callback);

  // Device I/O for drivers: `on_readable` runs whenever `fd` is readable
  // (live buses only; others throw std::logic_error). unwatch() may be called
  // from any callback, including the fd's own.
  virtual void watch(int fd, std::function<void()> on_readable);
  virtual void unwatch(int fd);

  // The bus clock [us since the Unix epoch]: host time live, log time in a replay.
  virtual int64_t now() const = 0;
  // Whether now() is the host's clock (false: a log's or a test's).
  virtual bool is_live() const = 0;
  // Runs until stop(), SIGINT/SIGTERM (live) or the end of the input (replay);
  // returns the exit code (0 on a clean stop).
  virtual int run() = 0;
  void stop() { stopping_ = true; }
  bool stopping() const { return stopping_; }

  // Health: state (logged with its name when it changes), drops, errors.
  void set_state(int8_t state, std::string message);
  // A moment's problem: one warning line, and the next PROCESS_STATUS says it
  // (ProcessHealth::note_event) even if the state is OK again by then.
  void note_event(int8_t state, const std::string& message);
  void count_drop(const std::string& channel, int64_t count = 1);
  void count_error(const std::string& what) { health_.count_handler_error(what); }
  void record_processing_time(double seconds) { health_.record_processing_time(seconds); }
  ProcessHealth& health() { return health_; }
  const ProcessHealth& health() const { return health_; }
  const std::string& name() const { return name_; }
  const ProcessOptions& options() const { return options_; }
  void log_info(const std::string& text) const;
  void log_warning(const std::string& text) const;

  static constexpr int64_t kNow = INT64_MIN;

 protected:
  Bus(std::string name, ProcessOptions options, int32_t pid, int64_t start_utime);

  // Transport hooks.
  virtual void start_receiving(const std::string& channel) = 0;  // deliver() this channel from now on
  virtual bool send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) = 0;

  // For implementations: hand received bytes to the channel's handlers.
  void deliver(const std::string& channel, const uint8_t* data, std::size_t size, int64_t receive_utime);
  bool is_subscribed(const std::string& channel) const { return handlers_.count(channel) != 0; }
  const std::set<std::string>& advertised() const { return advertised_; }
  // Timers: the earliest due time (INT64_MAX if none); fire the ones due at `now`.
  int64_t next_timer_due() const;
  void fire_due_timers(int64_t now);
  // Time jumped back (a log played twice): every timer is due one period after `now`.
  void restart_timers(int64_t now);
  // The start (first status) and the end (finish callbacks, last status) of run().
  void begin_run();
  void end_run();

 private:
  struct Subscriber {
    RawHandler handler;
    bool record_time = false;
  };
  struct Timer {
    int64_t period = 0;  // [us]
    int64_t next = 0;    // [us] bus time; 0 until the first run()
    std::function<void()> callback;
  };
  void add_subscriber(const std::string& channel, RawHandler handler, bool record_time);
  void publish_status();
  void flush_error_summary();
  void guarded(const std::string& what, const std::function<void()>& call);

  std::string name_;
  ProcessOptions options_;
  ProcessHealth health_;
  std::multimap<std::string, Subscriber> handlers_;
  std::set<std::string> advertised_;
  std::vector<Timer> timers_;
  std::vector<std::function<void()>> finish_;
  bool stopping_ = false;
  bool started_ = false;
  int64_t send_failures_ = 0;
};

template <class Msg>
void Bus::subscribe(const std::string& channel, Handler<Msg> handler, bool record_time) {
  add_subscriber(
      channel,
      [this, handler = std::move(handler)](const uint8_t* data, std::size_t size, const ReceiveInfo& info) {
        Msg msg{};
        const DecodeStatus status = decode_message(data, size, &msg);
        if (status != DecodeStatus::kOk) {
          health_.count_decode_error(info.channel, status, info.receive_utime);
          return;
        }
        health_.count_message(info.channel, channel_stats_t::SUBSCRIBED, info.receive_utime);
        handler(msg, info);
      },
      record_time);
}

template <class Msg>
bool Bus::publish(const std::string& channel, const Msg& msg, int64_t event_utime) {
  const int size = msg.getEncodedSize();
  std::vector<uint8_t> bytes(static_cast<std::size_t>(std::max(size, 0)));
  if (size < 0 || msg.encode(bytes.data(), 0, size) != size) {
    health_.count_handler_error("cannot encode a message for " + channel);
    return false;
  }
  return publish_raw(channel, bytes, event_utime);
}

}  // namespace slamer

// The skeleton every process runs on: LCM over UDP multicast, SIGINT/SIGTERM,
// timers, decode-error accounting and PROCESS_STATUS at 1 Hz.
//
// A process's main() parses its command line and config, builds its library
// objects, subscribes typed handlers here and calls run(). Handlers get
// decoded messages only: bytes that fail to decode are counted per channel,
// summarized in the log at most once per error_log_period, and never reach
// (or crash) the process. An exception escaping a handler is counted and
// logged the same way. SIGINT and SIGTERM are read from a signalfd, so run()
// returns normally and destructors run; programs this process starts must
// unblock the two signals (posix_spawnattr_setsigmask).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/process/command_line.hpp"
#include "common/process/decode.hpp"
#include "common/process/process_health.hpp"
#include "common/process/process_options.hpp"
#include "slamer/channel_stats_t.hpp"

namespace slamer {

// Host time now [us since the Unix epoch]; only process code reads clocks.
int64_t now_utime();

struct ReceiveInfo {
  std::string channel;
  int64_t receive_utime = 0;  // host time the bytes arrived [us]
};

class LcmProcess {
 public:
  // Throws std::runtime_error with a one-line reason if LCM cannot be opened.
  LcmProcess(std::string name, const std::string& lcm_url, ProcessOptions options);
  ~LcmProcess();
  LcmProcess(const LcmProcess&) = delete;
  LcmProcess& operator=(const LcmProcess&) = delete;

  template <class Msg>
  using Handler = std::function<void(const Msg&, const ReceiveInfo&)>;

  // Subscribes to exactly `channel` (not a pattern). With record_time, the
  // handler's run time goes into the processing-time p50/p99 of the status.
  template <class Msg>
  void subscribe(const std::string& channel, Handler<Msg> handler, bool record_time = false);

  // Returns false (and logs, rate-limited) if LCM could not send.
  template <class Msg>
  bool publish(const std::string& channel, const Msg& msg);

  // Publishes already encoded bytes (e.g. a message read from a log).
  bool publish_raw(const std::string& channel, const std::vector<uint8_t>& bytes) {
    return publish_bytes(channel, bytes);
  }

  // Calls `callback` every `period_s` seconds of steady time from run().
  void every(double period_s, std::function<void()> callback);

  void set_state(int8_t state, std::string message);
  void count_drop(const std::string& channel, int64_t count = 1);
  void record_processing_time(double seconds) { health_.record_processing_time(seconds); }
  const std::string& name() const { return name_; }
  ProcessHealth& health() { return health_; }

  // Runs until SIGINT/SIGTERM or stop(); returns the exit code (0 on a clean stop).
  int run();
  void stop() { stopping_ = true; }
  void log_info(const std::string& text) const;
  void log_warning(const std::string& text) const;

 private:
  struct Subscription;
  struct Timer {
    std::chrono::steady_clock::duration period;
    std::chrono::steady_clock::time_point next;
    std::function<void()> callback;
  };

  bool publish_bytes(const std::string& channel, const std::vector<uint8_t>& bytes);
  void dispatch(const lcm::ReceiveBuffer* buffer, Subscription& subscription);
  void publish_status();
  void flush_error_summary();

  std::string name_;
  ProcessOptions options_;
  ProcessHealth health_;
  int signal_fd_ = -1;
  std::unique_ptr<lcm::LCM> lcm_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  std::vector<Timer> timers_;
  bool stopping_ = false;
  int64_t publish_failures_ = 0;
};

struct LcmProcess::Subscription {
  LcmProcess* process = nullptr;
  std::string channel;
  bool record_time = false;
  // Decodes and calls the typed handler; returns the decode status.
  std::function<DecodeStatus(const void*, std::size_t, const ReceiveInfo&)> decode_and_handle;
};

template <class Msg>
void LcmProcess::subscribe(const std::string& channel, Handler<Msg> handler, bool record_time) {
  auto subscription = std::make_unique<Subscription>();
  subscription->process = this;
  subscription->channel = channel;
  subscription->record_time = record_time;
  subscription->decode_and_handle = [handler = std::move(handler)](const void* data, std::size_t size,
                                                                   const ReceiveInfo& info) {
    Msg msg;
    const DecodeStatus status = decode_message(data, size, &msg);
    if (status == DecodeStatus::kOk) {
      handler(msg, info);
    }
    return status;
  };
  health_.add_channel(channel, channel_stats_t::SUBSCRIBED);
  // LCM treats the channel as a regular expression; quote it so "A.B" is literal.
  std::string pattern;
  for (const char c : channel) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) {
      pattern += '\\';
    }
    pattern += c;
  }
  lcm_->subscribeFunction(
      pattern,
      +[](const lcm::ReceiveBuffer* buffer, const std::string&, Subscription* self) {
        self->process->dispatch(buffer, *self);
      },
      subscription.get());
  subscriptions_.push_back(std::move(subscription));
}

template <class Msg>
bool LcmProcess::publish(const std::string& channel, const Msg& msg) {
  const int size = msg.getEncodedSize();
  std::vector<uint8_t> bytes(static_cast<std::size_t>(size));
  if (msg.encode(bytes.data(), 0, size) != size) {
    health_.count_handler_error("cannot encode a message for " + channel);
    return false;
  }
  return publish_bytes(channel, bytes);
}

// The program's config from --config FILE, or its defaults without --config.
template <class Config>
Config load_config(const CommandLine& command_line) {
  Config config;
  if (command_line.has("config")) {
    config = load_options<Config>(command_line.get("config"));
  }
  return config;
}

// Runs a program's body with the common command line (--config, --lcm-url,
// --help) declared. `declare` adds program-specific options. Usage errors exit
// 2, config and runtime errors exit 1, each with one line on stderr.
int process_main(int argc, const char* const argv[], const std::string& program, const std::string& summary,
                 const std::function<void(CommandLine&)>& declare, const std::function<int(const CommandLine&)>& body);

}  // namespace slamer

// The live bus (bus.hpp): LCM over UDP multicast, the host clock, timers in
// steady time, SIGINT/SIGTERM read from a signalfd so run() returns normally
// and destructors run (programs this process starts must unblock the two
// signals: posix_spawnattr_setsigmask), and device file descriptors polled in
// the same loop as LCM's.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "common/process/bus.hpp"
#include "common/process/stop_signals.hpp"

namespace slamer {

// Host time now [us since the Unix epoch]; only process code reads clocks.
int64_t now_utime();

// LCM treats a channel as a regular expression: the pattern that matches exactly `channel`.
std::string literal_pattern(const std::string& channel);

class LcmBus final : public Bus {
 public:
  // Throws std::runtime_error with a one-line reason if LCM cannot be opened.
  LcmBus(std::string name, const std::string& lcm_url, ProcessOptions options);
  ~LcmBus() override;

  void watch(int fd, std::function<void()> on_readable) override;
  void unwatch(int fd) override;
  int64_t now() const override { return now_utime(); }
  bool is_live() const override { return true; }
  int run() override;

 private:
  void start_receiving(const std::string& channel) override;
  bool send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) override;

  StopSignals stop_signals_;  // before lcm_: blocked before LCM starts its threads, which inherit the mask
  std::unique_ptr<lcm::LCM> lcm_;
  std::map<int, std::function<void()>> watched_;
  struct Context;
  std::vector<std::unique_ptr<std::string>> channels_;
  std::vector<std::unique_ptr<Context>> contexts_;  // what LCM's callbacks get
};

}  // namespace slamer

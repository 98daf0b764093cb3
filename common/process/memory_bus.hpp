// The in-memory bus (bus.hpp) for tests of a whole program's wiring without
// sockets: the test injects encoded messages at bus times, runs the bus up to
// a time (timers fire in order, in bus time) and reads what was published.
// Publications loop back to the program's own subscribers, as on LCM.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "common/process/bus.hpp"

namespace slamer {

struct PublishedMessage {
  std::string channel;
  std::vector<uint8_t> bytes;
  int64_t utime = 0;  // bus time it was published
};

class MemoryBus final : public Bus {
 public:
  MemoryBus(std::string name, int64_t start_utime, ProcessOptions options = {});

  // Queues bytes (any bytes: garbage too) to arrive on `channel` at `utime`
  // (not before the current time).
  void inject(const std::string& channel, std::vector<uint8_t> bytes, int64_t utime);
  template <class Msg>
  void inject(const std::string& channel, const Msg& msg, int64_t utime);

  // Delivers what is due and fires timers, in time order, until `utime` (or stop()).
  void run_until(int64_t utime);
  // Starts the run (first PROCESS_STATUS); run_until() calls it when needed.
  void start();
  // Ends the run: the finish callbacks and the last PROCESS_STATUS.
  void finish();
  // Everything injected, then finish(); returns 0.
  int run() override;

  int64_t now() const override { return now_; }
  bool is_live() const override { return false; }

  const std::vector<PublishedMessage>& published() const { return published_; }
  // The messages of type Msg published on `channel`, decoded.
  template <class Msg>
  std::vector<Msg> published_on(const std::string& channel) const;

 private:
  struct Pending {
    std::string channel;
    std::vector<uint8_t> bytes;
    int64_t utime;
  };
  void start_receiving(const std::string&) override {}
  bool send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) override;

  int64_t now_;
  bool started_ = false;
  bool finished_ = false;
  std::deque<Pending> pending_;  // in time order
  std::vector<PublishedMessage> published_;
};

template <class Msg>
void MemoryBus::inject(const std::string& channel, const Msg& msg, int64_t utime) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  inject(channel, std::move(bytes), utime);
}

template <class Msg>
std::vector<Msg> MemoryBus::published_on(const std::string& channel) const {
  std::vector<Msg> messages;
  for (const PublishedMessage& message : published_) {
    Msg msg{};
    if (message.channel == channel &&
        decode_message(message.bytes.data(), message.bytes.size(), &msg) == DecodeStatus::kOk) {
      messages.push_back(std::move(msg));
    }
  }
  return messages;
}

}  // namespace slamer

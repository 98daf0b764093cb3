// Records decoded messages of chosen channels from a live LCM URL for
// process-level tests, with their arrival order kept per channel.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/process/decode.hpp"

namespace slamer::test {

class LcmCapture {
 public:
  explicit LcmCapture(const std::string& url) : lcm_(url) {}
  LcmCapture(const LcmCapture&) = delete;
  LcmCapture& operator=(const LcmCapture&) = delete;

  // Messages of `channel` that decode as Msg go into *store (which must outlive this).
  template <class Msg>
  void capture(const std::string& channel, std::vector<Msg>* store) {
    handlers_.push_back(std::make_unique<Handler>([store](const lcm::ReceiveBuffer* buffer) {
      Msg msg;
      if (decode_message(buffer->data, buffer->data_size, &msg) == DecodeStatus::kOk) {
        store->push_back(msg);
      }
    }));
    lcm_.subscribeFunction(
        channel, +[](const lcm::ReceiveBuffer* b, const std::string&, Handler* handler) { (*handler)(b); },
        handlers_.back().get());
  }

  // Handles messages until `done` or the timeout (false then); `every_50ms` runs every 50 ms.
  bool pump_until(const std::function<bool()>& done, double timeout_s, const std::function<void()>& every_50ms = {}) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    auto next = std::chrono::steady_clock::now();
    while (!done()) {
      if (std::chrono::steady_clock::now() >= deadline) {
        return false;
      }
      if (every_50ms && std::chrono::steady_clock::now() >= next) {
        every_50ms();
        next += std::chrono::milliseconds(50);
      }
      if (lcm_.handleTimeout(5) > 0) {
        while (lcm_.handleTimeout(0) > 0) {  // drain: 200 Hz streams must not pile up behind us
        }
      }
    }
    return true;
  }
  void pump_for(double seconds, const std::function<void()>& every_50ms = {}) {
    pump_until([] { return false; }, seconds, every_50ms);
  }
  lcm::LCM& lcm() { return lcm_; }  // to publish

 private:
  using Handler = std::function<void(const lcm::ReceiveBuffer*)>;
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<Handler>> handlers_;
};

}  // namespace slamer::test

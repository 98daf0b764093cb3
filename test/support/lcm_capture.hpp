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

  // Handles messages until `done` or the timeout; false on timeout.
  bool pump_until(const std::function<bool()>& done, double timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done()) {
      if (std::chrono::steady_clock::now() >= deadline) {
        return false;
      }
      if (lcm_.handleTimeout(5) > 0) {
        while (lcm_.handleTimeout(0) > 0) {  // drain: 200 Hz streams must not pile up behind us
        }
      }
    }
    return true;
  }
  void pump_for(double seconds) {
    pump_until([] { return false; }, seconds);
  }

 private:
  using Handler = std::function<void(const lcm::ReceiveBuffer*)>;
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<Handler>> handlers_;
};

}  // namespace slamer::test

// The test's own end of a live LCM bus, for process-level tests: publishes
// typed messages or raw bytes (bad input on purpose), and collects what the
// processes under test publish, decoded per channel with its receive time.
// Undecodable messages are counted, never stored.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "common/process/decode.hpp"

namespace slamer::test {

int64_t wall_utime();  // the host clock, Unix epoch [us]

template <class Msg>
struct Received {
  Msg msg;
  int64_t receive_utime = 0;  // wall_utime() when the test handled it
};

class LcmTestBus {
 public:
  explicit LcmTestBus(const std::string& url);
  LcmTestBus(const LcmTestBus&) = delete;
  LcmTestBus& operator=(const LcmTestBus&) = delete;
  bool good() { return lcm_.good(); }

  void publish_raw(const std::string& channel, const std::vector<uint8_t>& bytes);
  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    publish_raw(channel, encode(msg));
  }
  template <class Msg>
  static std::vector<uint8_t> encode(const Msg& msg) {
    std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  }

  // Everything decoded on `channel` from now on; the reference stays valid for the bus's life.
  template <class Msg>
  const std::deque<Received<Msg>>& collect(const std::string& channel) {
    auto store = std::make_shared<std::deque<Received<Msg>>>();
    stores_.push_back(store);
    subscribe(channel, [this, store](const uint8_t* data, std::size_t size) {
      Received<Msg> r;
      if (decode_message(data, size, &r.msg) == DecodeStatus::kOk) {
        r.receive_utime = wall_utime();
        store->push_back(std::move(r));
      } else {
        ++undecodable_;
      }
    });
    return *store;
  }

  // Handles messages until `done` is true (true) or `timeout_s` passes
  // (false); `tick` runs every 50 ms. Drains all that is queued each time
  // round, so fast streams do not pile up behind the test.
  bool pump_until(const std::function<bool()>& done, double timeout_s, const std::function<void()>& tick = {});
  void pump_for(double seconds, const std::function<void()>& tick = {});
  int64_t undecodable() const { return undecodable_; }

 private:
  using Handler = std::function<void(const uint8_t*, std::size_t)>;
  void subscribe(const std::string& channel, Handler handler);

  lcm::LCM lcm_;
  std::vector<std::shared_ptr<void>> stores_;
  std::vector<std::unique_ptr<Handler>> handlers_;
  int64_t undecodable_ = 0;
};

}  // namespace slamer::test

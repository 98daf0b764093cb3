#include "test/support/lcm_test_bus.hpp"

namespace slamer::test {

int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

LcmTestBus::LcmTestBus(const std::string& url) : lcm_(url) {}

void LcmTestBus::publish_raw(const std::string& channel, const std::vector<uint8_t>& bytes) {
  lcm_.publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size()));
}

void LcmTestBus::subscribe(const std::string& channel, Handler handler) {
  handlers_.push_back(std::make_unique<Handler>(std::move(handler)));
  // subscribeFunction with a context, as the stack does: LCM's member-function
  // subscription trips UBSan's vptr check inside lcm-cpp-impl.hpp.
  lcm_.subscribeFunction(
      channel,
      +[](const lcm::ReceiveBuffer* buffer, const std::string&, Handler* h) {
        (*h)(static_cast<const uint8_t*>(buffer->data), buffer->data_size);
      },
      handlers_.back().get());
}

bool LcmTestBus::pump_until(const std::function<bool()>& done, double timeout_s, const std::function<void()>& tick) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  auto next_tick = std::chrono::steady_clock::now();
  while (!done()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      return false;
    }
    if (tick && now >= next_tick) {
      tick();
      next_tick += std::chrono::milliseconds(50);
    }
    if (lcm_.handleTimeout(5) > 0) {
      while (lcm_.handleTimeout(0) > 0) {
      }
    }
  }
  return true;
}

void LcmTestBus::pump_for(double seconds, const std::function<void()>& tick) {
  pump_until([] { return false; }, seconds, tick);
}

}  // namespace slamer::test

// The live bus over real LCM multicast, in one process: what LCM itself would
// lose quietly, the bus keeps.
#include "common/process/lcm_bus.hpp"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "test/support/child_process.hpp"

namespace slamer {
namespace {

using namespace std::chrono_literals;

// LCM's default queue (30 messages a channel) dropped what came while a
// handler was busy: 0.3 s of 100 Hz odometry behind one slow scan update.
TEST(LcmBus, AHandlerBusyForASecondLosesNoneOfTheMessagesThatCameMeanwhile) {
  const std::string url = test::unique_lcm_url(3);
  LcmBus bus("slamer-test-bus", url, ProcessOptions{});
  constexpr int kMessages = 300;
  int received = 0;
  bus.subscribe_raw("BURST", [&](const uint8_t*, std::size_t, const ReceiveInfo&) {
    if (received++ == 0) {
      std::this_thread::sleep_for(1s);  // meanwhile the other 299 come
    }
  });
  std::atomic<bool> started{false};
  std::atomic<bool> sent{false};
  std::thread publisher([&] {
    lcm::LCM lcm(url);
    while (!started) {
      std::this_thread::sleep_for(10ms);
    }
    const std::vector<uint8_t> payload(200, 7);
    for (int i = 0; i < kMessages; ++i) {
      lcm.publish("BURST", payload.data(), static_cast<unsigned int>(payload.size()));
      std::this_thread::sleep_for(1ms);  // 1 kHz: well within the kernel's buffer
    }
    sent = true;
  });
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  bus.every(0.05, [&] {
    started = true;
    if ((sent && received >= kMessages) || std::chrono::steady_clock::now() > deadline) {
      bus.stop();
    }
  });
  EXPECT_EQ(bus.run(), 0);
  publisher.join();
  EXPECT_EQ(received, kMessages);
}

}  // namespace
}  // namespace slamer

#include "common/process/memory_bus.hpp"

#include <algorithm>
#include <limits>

namespace slamer {

MemoryBus::MemoryBus(std::string name, int64_t start_utime, ProcessOptions options)
    : Bus(std::move(name), std::move(options), 0, start_utime), now_(start_utime) {}

void MemoryBus::inject(const std::string& channel, std::vector<uint8_t> bytes, int64_t utime) {
  utime = std::max(utime, now_);
  // Stable: messages at the same time arrive in the order injected.
  const auto at = std::upper_bound(pending_.begin(), pending_.end(), utime,
                                   [](int64_t t, const Pending& p) { return t < p.utime; });
  pending_.insert(at, Pending{channel, std::move(bytes), utime});
}

bool MemoryBus::send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) {
  published_.push_back({channel, bytes, event_utime});
  if (is_subscribed(channel)) {
    inject(channel, bytes, now_);  // LCM loops a process's own messages back
  }
  return true;
}

void MemoryBus::start() {
  if (!started_) {
    started_ = true;
    begin_run();
  }
}

void MemoryBus::run_until(int64_t utime) {
  start();
  while (!stopping()) {
    const int64_t next_message = pending_.empty() ? std::numeric_limits<int64_t>::max() : pending_.front().utime;
    const int64_t next_timer = next_timer_due();
    const int64_t next = std::min(next_message, next_timer);
    if (next > utime) {
      break;
    }
    now_ = next;
    if (next_message <= next_timer) {
      Pending message = std::move(pending_.front());
      pending_.pop_front();
      deliver(message.channel, message.bytes.data(), message.bytes.size(), message.utime);
    } else {
      fire_due_timers(now_);
    }
  }
  if (!stopping()) {
    now_ = std::max(now_, utime);
  }
}

void MemoryBus::finish() {
  if (!finished_) {
    start();
    finished_ = true;
    end_run();
  }
}

int MemoryBus::run() {
  run_until(pending_.empty() ? now_ : pending_.back().utime);
  finish();
  return 0;
}

}  // namespace slamer

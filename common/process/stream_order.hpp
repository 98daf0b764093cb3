// The order of a stream of time-stamped messages. A message no newer than the
// last accepted one is stale (a duplicate, or delivered out of order) and is
// dropped; a jump back by more than `restart_after_us` is not jitter but a new
// run (a log replayed from the top, a clock reset), and the stream starts over.
// Every input stream of the stack uses this one rule.
#pragma once

#include <cstdint>
#include <optional>

namespace slamer {

enum class Arrival {
  kInOrder,  // newer than the last: accept
  kStale,    // not newer, but by less than restart_after_us: drop and count
  kRestart,  // far older: accept it as the first of a new run, after starting over
};

class StreamOrder {
 public:
  static constexpr int64_t kDefaultRestartAfterUs = 1'000'000;

  explicit StreamOrder(int64_t restart_after_us = kDefaultRestartAfterUs) : restart_after_us_(restart_after_us) {}

  Arrival check(int64_t utime) {
    if (last_ && utime <= *last_) {
      if (*last_ - utime <= restart_after_us_) {
        return Arrival::kStale;
      }
      last_ = utime;
      return Arrival::kRestart;
    }
    last_ = utime;
    return Arrival::kInOrder;
  }
  void reset() { last_.reset(); }
  const std::optional<int64_t>& last() const { return last_; }

 private:
  int64_t restart_after_us_;
  std::optional<int64_t> last_;
};

}  // namespace slamer

#include "common/process/bus.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/process/log.hpp"

namespace slamer {

const char* process_state_name(int8_t process_state) {
  switch (process_state) {
    case process_status_t::OK:
      return "OK";
    case process_status_t::DEGRADED:
      return "DEGRADED";
    case process_status_t::ERROR:
      return "ERROR";
    default:
      return "UNKNOWN";
  }
}

Bus::Bus(std::string name, ProcessOptions options, int32_t pid, int64_t start_utime)
    : name_(std::move(name)), options_(std::move(options)), health_(name_, pid, start_utime) {
  health_.add_channel(options_.status_channel, channel_stats_t::PUBLISHED);
  advertised_.insert(options_.status_channel);
  every(options_.status_period, [this] { publish_status(); });
  every(options_.error_log_period, [this] { flush_error_summary(); });
}

void Bus::add_subscriber(const std::string& channel, RawHandler handler, bool record_time) {
  if (!is_subscribed(channel)) {
    health_.add_channel(channel, channel_stats_t::SUBSCRIBED);
    start_receiving(channel);
  }
  handlers_.emplace(channel, Subscriber{std::move(handler), record_time});
}

void Bus::subscribe_raw(const std::string& channel, RawHandler handler, bool record_time) {
  add_subscriber(
      channel,
      [this, handler = std::move(handler)](const uint8_t* data, std::size_t size, const ReceiveInfo& info) {
        health_.count_message(info.channel, channel_stats_t::SUBSCRIBED, info.receive_utime);
        handler(data, size, info);
      },
      record_time);
}

void Bus::advertise(const std::string& channel) {
  advertised_.insert(channel);
  health_.add_channel(channel, channel_stats_t::PUBLISHED);
}

bool Bus::publish_raw(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) {
  if (!send(channel, bytes, event_utime == kNow ? now() : event_utime)) {
    health_.count_drop(channel, channel_stats_t::PUBLISHED);
    if (send_failures_++ == 0) {
      log_warning("cannot publish on " + channel + " (" + std::to_string(bytes.size()) +
                  " bytes); further failures are only counted");
    }
    return false;
  }
  health_.count_message(channel, channel_stats_t::PUBLISHED, now());
  return true;
}

void Bus::every(double period_s, std::function<void()> callback) {
  const int64_t period = std::llround(std::max(period_s, 1e-3) * 1e6);
  timers_.push_back(Timer{period, started_ ? now() + period : 0, std::move(callback)});
}

void Bus::at_finish(std::function<void()> callback) {
  finish_.push_back(std::move(callback));
}

void Bus::watch(int, std::function<void()>) {
  throw std::logic_error(name_ + ": this bus has no device I/O (file descriptors are watched only live)");
}

void Bus::unwatch(int) {
  throw std::logic_error(name_ + ": this bus has no device I/O");
}

void Bus::set_state(int8_t state, std::string message) {
  if (state != health_.state()) {
    const std::string text =
        std::string("state ") + process_state_name(state) + (message.empty() ? "" : ": " + message);
    if (state == process_status_t::OK) {
      log_info(text);
    } else {
      log_warning(text);
    }
  }
  health_.set_state(state, std::move(message));
}

void Bus::note_event(int8_t state, const std::string& message) {
  log_warning(message);
  health_.note_event(state, message);
}

void Bus::count_drop(const std::string& channel, int64_t count) {
  health_.count_drop(channel, channel_stats_t::SUBSCRIBED, count);
}

void Bus::log_info(const std::string& text) const {
  log_line(name_, LogLevel::kInfo, text);
}

void Bus::log_warning(const std::string& text) const {
  log_line(name_, LogLevel::kWarning, text);
}

void Bus::guarded(const std::string& what, const std::function<void()>& call) {
  try {
    call();
  } catch (const std::exception& e) {
    health_.count_handler_error(what + ": " + e.what());
  }
}

void Bus::deliver(const std::string& channel, const uint8_t* data, std::size_t size, int64_t receive_utime) {
  const ReceiveInfo info{channel, receive_utime};
  const auto [first, last] = handlers_.equal_range(channel);
  for (auto it = first; it != last; ++it) {
    const Subscriber& subscriber = it->second;
    const auto start = std::chrono::steady_clock::now();
    guarded(channel, [&] { subscriber.handler(data, size, info); });
    if (subscriber.record_time && is_live()) {
      health_.record_processing_time(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  }
}

int64_t Bus::next_timer_due() const {
  int64_t due = std::numeric_limits<int64_t>::max();
  for (const Timer& timer : timers_) {
    due = std::min(due, timer.next);
  }
  return due;
}

void Bus::fire_due_timers(int64_t now) {
  // Index loop: a callback may add timers.
  for (std::size_t i = 0; i < timers_.size() && !stopping_; ++i) {
    if (now < timers_[i].next) {
      continue;
    }
    timers_[i].next += timers_[i].period;
    if (timers_[i].next <= now) {  // fell behind (a long handler, a gap in a log): do not burst
      timers_[i].next = now + timers_[i].period;
    }
    const std::function<void()> callback = timers_[i].callback;
    guarded("timer", callback);
  }
}

void Bus::restart_timers(int64_t now) {
  for (Timer& timer : timers_) {
    timer.next = now + timer.period;
  }
}

void Bus::begin_run() {
  started_ = true;
  restart_timers(now());
  log_info(is_live() ? "running" : "replaying");
  publish_status();
}

void Bus::end_run() {
  for (const auto& callback : finish_) {
    guarded("at finish", callback);
  }
  flush_error_summary();
  publish_status();
}

void Bus::publish_status() {
  publish(options_.status_channel, health_.take_status(now()));
}

void Bus::flush_error_summary() {
  const std::string summary = health_.take_error_summary();
  if (!summary.empty()) {
    log_warning(summary);
  }
}

}  // namespace slamer

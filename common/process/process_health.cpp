#include "common/process/process_health.hpp"

#include <algorithm>

#include "slamer/channel_stats_t.hpp"

namespace slamer {

ProcessHealth::ProcessHealth(std::string process_name, int32_t pid, int64_t start_utime)
    : process_name_(std::move(process_name)), pid_(pid), start_utime_(start_utime) {}

void ProcessHealth::add_channel(const std::string& channel, int8_t direction) {
  channels_[{channel, direction}];
}

void ProcessHealth::count_message(const std::string& channel, int8_t direction, int64_t utime) {
  ChannelCounters& counters = channels_[{channel, direction}];
  ++counters.messages;
  counters.last_utime = utime;
}

void ProcessHealth::count_decode_error(const std::string& channel, DecodeStatus status, int64_t utime) {
  ChannelCounters& counters = channels_[{channel, channel_stats_t::SUBSCRIBED}];
  ++counters.decode_errors;
  ++counters.unreported_errors;
  counters.last_error = status;
  counters.last_utime = utime;
}

void ProcessHealth::count_drop(const std::string& channel, int8_t direction, int64_t count) {
  channels_[{channel, direction}].drops += count;
}

void ProcessHealth::add_drop_source(const std::string& channel, int8_t direction, std::function<int64_t()> drops) {
  channels_[{channel, direction}].drop_sources.push_back(std::move(drops));
}

void ProcessHealth::count_handler_error(const std::string& what) {
  ++unreported_handler_errors_;
  last_handler_error_ = what;
}

void ProcessHealth::record_processing_time(double seconds) {
  processing_time_.add(seconds);
}

void ProcessHealth::set_state(int8_t state, std::string message) {
  state_ = state;
  message_ = std::move(message);
}

void ProcessHealth::note_event(int8_t state, std::string message) {
  event_state_ = std::max(event_state_, state);
  if (events_.size() < kEventsKept) {
    events_.push_back(std::move(message));
  } else {
    ++events_more_;
  }
}

process_status_t ProcessHealth::take_status(int64_t now_utime) {
  process_status_t s = status(now_utime);
  if (!events_.empty()) {
    s.state = std::max(state_, event_state_);
    s.message.clear();
    for (const std::string& e : events_) {
      s.message += (s.message.empty() ? "" : "; ") + e;
    }
    if (events_more_ > 0) {
      s.message += "; " + std::to_string(events_more_) + " more";
    }
    s.message +=
        " (now " + (message_.empty() ? std::string(state_ == process_status_t::OK ? "OK" : "-") : message_) + ")";
  }
  event_state_ = process_status_t::OK;
  events_.clear();
  events_more_ = 0;
  return s;
}

process_status_t ProcessHealth::status(int64_t now_utime) const {
  process_status_t status;
  status.utime = now_utime;
  status.process = process_name_;
  status.pid = pid_;
  status.state = state_;
  status.message = message_;
  status.uptime = static_cast<double>(now_utime - start_utime_) * 1e-6;
  status.messages_in = 0;
  status.messages_out = 0;
  status.decode_errors = 0;
  status.drops = 0;
  status.processing_time_p50 = processing_time_.percentile(0.5);
  status.processing_time_p99 = processing_time_.percentile(0.99);
  for (const auto& [key, counters] : channels_) {
    channel_stats_t stats;
    stats.channel = key.first;
    stats.direction = key.second;
    stats.messages = counters.messages;
    stats.decode_errors = counters.decode_errors;
    stats.drops = counters.drops;
    for (const auto& source : counters.drop_sources) {
      stats.drops += source();
    }
    stats.last_utime = counters.last_utime;
    status.channels.push_back(stats);
    (key.second == channel_stats_t::SUBSCRIBED ? status.messages_in : status.messages_out) += counters.messages;
    status.decode_errors += counters.decode_errors;
    status.drops += stats.drops;
  }
  status.nchannels = static_cast<int32_t>(status.channels.size());
  return status;
}

std::string ProcessHealth::take_error_summary() {
  int64_t total = 0;
  std::string parts;
  for (auto& [key, counters] : channels_) {
    if (counters.unreported_errors == 0) {
      continue;
    }
    total += counters.unreported_errors;
    parts += (parts.empty() ? "" : ", ") + key.first + " " + std::to_string(counters.unreported_errors) + " (" +
             std::string(describe(counters.last_error)) + ")";
    counters.unreported_errors = 0;
  }
  std::string summary;
  if (total > 0) {
    summary = std::to_string(total) + " decode error" + (total == 1 ? "" : "s") + ": " + parts;
  }
  if (unreported_handler_errors_ > 0) {
    summary += std::string(summary.empty() ? "" : "; ") + std::to_string(unreported_handler_errors_) +
               " handler error" + (unreported_handler_errors_ == 1 ? "" : "s") + ", last: " + last_handler_error_;
    unreported_handler_errors_ = 0;
  }
  return summary;
}

}  // namespace slamer

#include "common/process/log_bus.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "common/process/log.hpp"
#include "slamer/process_status_t.hpp"

namespace slamer {
namespace {

// Time back by more than this is a new run, not the jitter of a log whose
// events are written at their publish times (stream_order.hpp's rule).
constexpr int64_t kRestartAfterUs = 1'000'000;

std::unique_ptr<lcm::LogFile> open_output(const std::string& path) {
  auto out = std::make_unique<lcm::LogFile>(path, "w");
  if (!out->good()) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent)) {
      throw std::runtime_error("cannot write log " + path + ": folder " + parent.string() + " does not exist");
    }
    throw std::runtime_error("cannot write log " + path);
  }
  return out;
}

}  // namespace

LogBus::LogBus(std::string name, const std::string& in_path, const std::string& out_path, ProcessOptions options)
    : Bus(std::move(name), std::move(options), 0, 0), out_path_(out_path), in_path_(in_path) {
  std::error_code error;
  if (std::filesystem::is_directory(in_path, error)) {
    throw std::runtime_error(in_path + " is a folder, not an LCM log");
  }
  if (!std::filesystem::exists(in_path, error)) {
    throw std::runtime_error("no such log: " + in_path);
  }
  if (std::filesystem::exists(out_path, error) &&
      std::filesystem::equivalent(std::filesystem::path(in_path), std::filesystem::path(out_path), error)) {
    throw std::runtime_error("the output log must not be the input log " + in_path);
  }
  in_ = std::make_unique<EventLogReader>(in_path);
  out_ = open_output(out_path);
}

LogBus::LogBus(std::string name, const std::string& out_path, int64_t start_utime, ProcessOptions options)
    : Bus(std::move(name), std::move(options), 0, start_utime), out_path_(out_path), now_(start_utime) {
  out_ = open_output(out_path);
}

LogBus::~LogBus() = default;

void LogBus::write(const std::string& channel, const uint8_t* data, std::size_t size, int64_t timestamp) {
  lcm::LogEvent event;
  event.timestamp = timestamp;
  event.channel = channel;
  event.datalen = static_cast<int32_t>(size);
  event.data = const_cast<uint8_t*>(data);
  if (out_->writeEvent(&event) != 0) {
    throw std::runtime_error("cannot write to " + out_path_);
  }
  ++stats_.events_out;
}

bool LogBus::send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t event_utime) {
  write(channel, bytes.data(), bytes.size(), event_utime);
  return true;
}

bool LogBus::is_own_status(const LogEvent& event) const {
  if (event.channel != options().status_channel) {
    return false;
  }
  process_status_t status{};
  return decode_message(event.data.data(), event.data.size(), &status) == DecodeStatus::kOk && status.process == name();
}

void LogBus::fire_timers_until(int64_t utime) {
  for (int64_t due = next_timer_due(); due <= utime && !stopping(); due = next_timer_due()) {
    now_ = due;
    fire_due_timers(due);
  }
}

int LogBus::run() {
  if (!in_) {
    begin_run();
    while (!stopping()) {
      fire_timers_until(next_timer_due());
    }
    end_run();
    return 0;
  }
  std::optional<LogEvent> event = in_->next();
  if (!event) {
    throw std::runtime_error(in_path_ + (in_->damaged_bytes() > 0 ? " is not an LCM log (no event in it)"
                                                                  : " is empty: no events to replay"));
  }
  now_ = event->timestamp;
  begin_run();
  const bool terminal = isatty(STDERR_FILENO) != 0;
  for (; event && !stopping(); event = in_->next()) {
    ++stats_.events_in;
    if (event->timestamp < now_ - kRestartAfterUs) {  // a new run in the log: the clock starts over
      now_ = event->timestamp;
      restart_timers(now_);
    } else if (event->timestamp > now_) {  // (a little back is jitter: the clock does not go back)
      fire_timers_until(event->timestamp);
      now_ = event->timestamp;
    }
    const bool left_out =
        event->channel == options().status_channel ? is_own_status(*event) : advertised().count(event->channel) != 0;
    if (left_out) {
      ++stats_.events_left_out;
      continue;
    }
    write(event->channel, event->data.data(), event->data.size(), event->timestamp);
    if (is_subscribed(event->channel)) {
      ++stats_.events_handled;
      deliver(event->channel, event->data.data(), event->data.size(), event->timestamp);
    }
    if (terminal && stats_.events_in % 5000 == 0) {
      std::fprintf(stderr, "\r%s: %3.0f%%", name().c_str(), 100.0 * in_->fraction_read());
    }
  }
  if (terminal) {
    std::fprintf(stderr, "\n");
  }
  if (const std::string problems = in_->problems(); !problems.empty()) {
    log_warning(problems);
  }
  end_run();
  return 0;
}

}  // namespace slamer

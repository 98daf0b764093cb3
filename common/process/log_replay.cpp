#include "common/process/log_replay.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <stdexcept>

#include "common/process/event_log.hpp"
#include "common/process/log.hpp"

namespace slamer {

ReplayStats replay_log(const std::string& program, const std::string& in_path, const std::string& out_path,
                       const std::set<std::string>& channels, const std::set<std::string>& replaced,
                       const std::function<void(const std::string&, const std::vector<uint8_t>&, int64_t,
                                                std::vector<OutputEvent>*)>& handle,
                       const std::function<void(std::vector<OutputEvent>*)>& finish) {
  if (std::filesystem::weakly_canonical(in_path) == std::filesystem::weakly_canonical(out_path)) {
    throw std::runtime_error("the output log must not be the input log " + in_path);
  }
  EventLogReader in(in_path);
  lcm::LogFile out(out_path, "w");
  if (!out.good()) {
    throw std::runtime_error("cannot write log " + out_path);
  }
  ReplayStats stats;
  const auto write = [&](const std::string& channel, const void* data, int32_t length, int64_t timestamp) {
    lcm::LogEvent event;
    event.timestamp = timestamp;
    event.channel = channel;
    event.datalen = length;
    event.data = const_cast<void*>(data);
    if (out.writeEvent(&event) != 0) {
      throw std::runtime_error("cannot write to " + out_path);
    }
    ++stats.events_out;
  };
  const bool terminal = isatty(STDERR_FILENO) != 0;
  std::vector<OutputEvent> outputs;
  int64_t last_timestamp = 0;
  while (const std::optional<LogEvent> event = in.next()) {
    ++stats.events_in;
    last_timestamp = event->timestamp;
    if (replaced.count(event->channel) != 0) {
      ++stats.events_replaced;
      continue;
    }
    write(event->channel, event->data.data(), static_cast<int32_t>(event->data.size()), event->timestamp);
    if (channels.count(event->channel) != 0) {
      ++stats.events_handled;
      outputs.clear();
      try {
        handle(event->channel, event->data, event->timestamp, &outputs);
      } catch (const std::exception&) {
        ++stats.handler_errors;  // the event is skipped, the replay goes on
      }
      for (const OutputEvent& output : outputs) {
        write(output.channel, output.bytes.data(), static_cast<int32_t>(output.bytes.size()), event->timestamp);
      }
    }
    if (terminal && stats.events_in % 5000 == 0) {
      std::fprintf(stderr, "\r%s: %3.0f%%", program.c_str(), 100.0 * in.fraction_read());
    }
  }
  if (terminal) {
    std::fprintf(stderr, "\n");
  }
  if (const std::string problems = in.problems(); !problems.empty()) {
    log_line(program, LogLevel::kWarning, problems);
  }
  if (finish) {
    outputs.clear();
    finish(&outputs);
    for (const OutputEvent& output : outputs) {
      write(output.channel, output.bytes.data(), static_cast<int32_t>(output.bytes.size()), last_timestamp);
    }
  }
  return stats;
}

}  // namespace slamer

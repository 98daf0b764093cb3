#include "common/process/log.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>

namespace slamer {

void log_line(std::string_view process, LogLevel level, std::string_view text) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%S", &utc);
  const char* name = level == LogLevel::kInfo ? "INFO" : level == LogLevel::kWarning ? "WARN" : "ERROR";
  // Keep the message on one line whatever it contains.
  std::string line(text);
  for (char& c : line) {
    if (c == '\n' || c == '\r') {
      c = ' ';
    }
  }
  std::fprintf(stderr, "%s.%03dZ %.*s %s %s\n", stamp, static_cast<int>(millis), static_cast<int>(process.size()),
               process.data(), name, line.c_str());
}

}  // namespace slamer

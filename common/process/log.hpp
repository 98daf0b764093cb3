// One-line log messages on stderr: "2026-11-23T09:45:01.123Z slamer-x INFO text".
#pragma once

#include <string_view>

namespace slamer {

enum class LogLevel { kInfo, kWarning, kError };

void log_line(std::string_view process, LogLevel level, std::string_view text);

}  // namespace slamer

// The "process" section every process's config file has.
#pragma once

#include <string>

#include "common/config/config_reader.hpp"

namespace slamer {

struct ProcessOptions {
  std::string status_channel = "PROCESS_STATUS";
  double status_period = 1.0;     // [s] between PROCESS_STATUS messages
  double error_log_period = 1.0;  // [s] at most one decode-error summary line per period
};
void read_options(const ConfigReader& reader, ProcessOptions* options);

}  // namespace slamer

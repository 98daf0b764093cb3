// Runs a program to its end (slamer-bench's localizer run): its exit code and CPU time.
#pragma once

#include <string>
#include <vector>

namespace slamer {

struct ProgramRun {
  int exit_code = -1;        // 128 + signal if killed by one
  double cpu_seconds = 0.0;  // user + system
};

// Throws std::runtime_error if it cannot be started.
ProgramRun run_program(const std::string& program, const std::vector<std::string>& args);

}  // namespace slamer

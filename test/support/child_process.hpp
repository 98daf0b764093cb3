// Starts a real program as a child process for process-level tests: output
// to files, SIGINT/SIGTERM unblocked in the child, stopped on destruction
// (SIGTERM, then SIGKILL after 2 s).
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace slamer::test {

class ChildProcess {
 public:
  // Starts `program` with `args`; stdout and stderr go to files in a fresh temp dir.
  ChildProcess(const std::string& program, const std::vector<std::string>& args);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  void signal(int signo) const;
  // Exit status if it exited within `timeout_s` (128 + signal if killed by one).
  std::optional<int> wait(double timeout_s);
  std::string stdout_text() const;
  std::string stderr_text() const;

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  std::string dir_;
};

// A multicast LCM URL on loopback; another test process running at the same time has its port
// with odds of 1 in 40000 (per pair of URLs).
std::string unique_lcm_url(int salt);

std::string binary_path(const std::string& name);  // build-tree bin/NAME

std::string read_file(const std::string& path);  // its bytes; "" if it cannot be read

}  // namespace slamer::test

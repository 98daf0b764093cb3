#include "test/support/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace slamer::test {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& args) {
  char pattern[] = "/tmp/slamer_child_XXXXXX";
  if (mkdtemp(pattern) == nullptr) {
    throw std::runtime_error("mkdtemp failed");
  }
  dir_ = pattern;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (dir_ + "/stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (dir_ + "/stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& arg : args) {
    argv.push_back(const_cast<char*>(arg.c_str()));
  }
  argv.push_back(nullptr);
  const int error = posix_spawn(&pid_, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (error != 0) {
    throw std::runtime_error("cannot start " + program + ": " + std::strerror(error));
  }
}

ChildProcess::~ChildProcess() {
  // SIGTERM first, as supervisor stops a program: it removes what it made (an
  // emulator's pty link or socket file); SIGKILL if it has not exited in 2 s.
  if (running()) {
    ::kill(pid_, SIGTERM);
    if (!wait(2.0)) {
      ::kill(pid_, SIGKILL);
      wait(5.0);
    }
  }
  std::error_code ignored;
  std::filesystem::remove_all(dir_, ignored);
}

bool ChildProcess::running() {
  if (exit_code_) {
    return false;
  }
  return !wait(0.0).has_value();
}

void ChildProcess::signal(int signo) const {
  ::kill(pid_, signo);
}

std::optional<int> ChildProcess::wait(double timeout_s) {
  if (exit_code_) {
    return exit_code_;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (true) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return exit_code_;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

std::string ChildProcess::stdout_text() const {
  return read_file(dir_ + "/stdout");
}
std::string ChildProcess::stderr_text() const {
  return read_file(dir_ + "/stderr");
}

std::string unique_lcm_url(int salt) {
  // Ports 20000-59999 from a hash of the process id and the salt: ctest runs each test case as its
  // own process, several at once and often with consecutive ids. The former (pid * 7 + salt) gave
  // process p's salt s and process p + 1's salt s - 7 one port, so two tests read each other's messages.
  uint64_t h = (static_cast<uint64_t>(getpid()) << 20) ^ static_cast<uint64_t>(static_cast<uint32_t>(salt));
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;  // splitmix64's finalizer
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  h ^= h >> 31;
  const int port = 20000 + static_cast<int>(h % 40000);
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

std::string binary_path(const std::string& name) {
  return std::string(SLAMER_BINARY_DIR "/bin/") + name;
}

}  // namespace slamer::test

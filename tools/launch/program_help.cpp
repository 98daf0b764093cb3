#include "tools/launch/program_help.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>

namespace slamer::launch {
namespace {

bool option_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}

bool lists(const std::string& help, const std::string& option) {
  for (std::size_t at = help.find(option); at != std::string::npos; at = help.find(option, at + 1)) {
    const std::size_t end = at + option.size();
    const bool starts = at == 0 || !option_char(help[at - 1]);
    if (starts && (end == help.size() || !option_char(help[end]))) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::string program_help(const std::string& program_path, double timeout_s) {
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) {
    return "";
  }
  const pid_t pid = fork();
  if (pid < 0) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return "";
  }
  if (pid == 0) {
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    const int null = open("/dev/null", O_RDONLY);
    dup2(null, STDIN_FILENO);
    dup2(pipe_fds[1], STDOUT_FILENO);
    dup2(pipe_fds[1], STDERR_FILENO);
    execl(program_path.c_str(), program_path.c_str(), "--help", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
    pollfd p{pipe_fds[0], POLLIN, 0};
    if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) {
      out.clear();  // no answer in time: nothing to compare
      break;
    }
    const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
    if (n <= 0 || out.size() > (1u << 20)) {
      break;
    }
    out.append(buffer, static_cast<std::size_t>(n));
  }
  close(pipe_fds[0]);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  return out;
}

std::vector<std::string> unlisted_options(const std::vector<std::string>& args, const std::string& help) {
  std::vector<std::string> unlisted;
  if (!lists(help, "--help") && help.find("--") == std::string::npos) {
    return unlisted;
  }
  for (const std::string& arg : args) {
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) {
      continue;
    }
    const std::string option = arg.substr(0, arg.find('='));
    if (!lists(help, option)) {
      unlisted.push_back(option);
    }
  }
  return unlisted;
}

}  // namespace slamer::launch

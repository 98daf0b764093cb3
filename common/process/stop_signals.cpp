#include "common/process/stop_signals.hpp"

#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace slamer {

StopSignals::StopSignals() {
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  if (pthread_sigmask(SIG_BLOCK, &stop, nullptr) != 0) {
    throw std::runtime_error("cannot block SIGINT/SIGTERM");
  }
  fd_ = signalfd(-1, &stop, SFD_NONBLOCK | SFD_CLOEXEC);
  if (fd_ < 0) {
    throw std::runtime_error(std::string("cannot create a signalfd: ") + std::strerror(errno));
  }
}

StopSignals::~StopSignals() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool StopSignals::requested() {
  signalfd_siginfo info{};
  while (::read(fd_, &info, sizeof(info)) == static_cast<ssize_t>(sizeof(info))) {
    requested_ = true;
    last_signal_ = static_cast<int>(info.ssi_signo);
  }
  return requested_;
}

bool StopSignals::wait(double seconds) {
  pollfd p{fd_, POLLIN, 0};
  const int timeout_ms = seconds > 0.0 ? static_cast<int>(std::lround(seconds * 1000.0)) : 0;
  ::poll(&p, 1, timeout_ms);
  return requested();
}

}  // namespace slamer

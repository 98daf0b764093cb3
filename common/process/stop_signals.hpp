// SIGINT and SIGTERM as a file descriptor, for a program's own poll loop (the
// device emulators): the signals are blocked, so they neither kill the process
// before it has removed what it made (a pty symlink, a socket file) nor
// interrupt its system calls; the loop polls fd() and stops once requested().
// Construct it before starting threads, which inherit the signal mask.
#pragma once

namespace slamer {

class StopSignals {
 public:
  StopSignals();  // throws std::runtime_error if the signals cannot be blocked
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  int fd() const { return fd_; }  // readable once a stop signal arrived
  // Whether SIGINT or SIGTERM arrived (consumes any pending ones; sticky).
  bool requested();
  // Sleeps up to `seconds`, waking early for a stop signal; returns requested().
  bool wait(double seconds);
  int last_signal() const { return last_signal_; }  // SIGINT or SIGTERM once requested(), else 0

 private:
  int fd_ = -1;
  bool requested_ = false;
  int last_signal_ = 0;
};

}  // namespace slamer

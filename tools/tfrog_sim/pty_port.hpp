// A pseudo-terminal standing in for the board's USB port: the master side is
// the emulator's, the slave is reached through a symlink (like a udev link).
// close() models the USB unplug: the driver's reads fail and the link vanishes.
#pragma once

#include <string>

namespace slamer {

class PtyPort {
 public:
  explicit PtyPort(std::string link) : link_(std::move(link)) {}
  ~PtyPort() { close(); }
  PtyPort(const PtyPort&) = delete;
  PtyPort& operator=(const PtyPort&) = delete;

  // Creates the pty (raw, non-blocking master) and points the link at it; throws on failure.
  void open();
  void close();
  bool is_open() const { return master_ >= 0; }
  int fd() const { return master_; }
  const std::string& slave_name() const { return slave_name_; }

 private:
  std::string link_;
  std::string slave_name_;
  int master_ = -1;
  int slave_ = -1;  // held open so the line settings stay raw between driver opens
};

}  // namespace slamer

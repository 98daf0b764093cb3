#include "tools/tfrog_sim/pty_port.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace slamer {

void PtyPort::open() {
  close();
  master_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0) {
    throw std::runtime_error(std::string("cannot create a pty: ") + std::strerror(errno));
  }
  char name[128];
  if (ptsname_r(master_, name, sizeof(name)) != 0) {
    throw std::runtime_error("ptsname failed");
  }
  slave_name_ = name;
  slave_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  termios tio{};
  if (slave_ < 0 || tcgetattr(slave_, &tio) != 0) {
    throw std::runtime_error("cannot open the pty slave " + slave_name_);
  }
  cfmakeraw(&tio);
  tcsetattr(slave_, TCSANOW, &tio);
  const std::string temporary = link_ + ".new";
  ::unlink(temporary.c_str());
  if (::symlink(name, temporary.c_str()) != 0 || std::rename(temporary.c_str(), link_.c_str()) != 0) {
    throw std::runtime_error("cannot link " + link_ + " -> " + slave_name_ + ": " + std::strerror(errno));
  }
}

void PtyPort::close() {
  if (master_ >= 0) {
    ::unlink(link_.c_str());
    ::close(master_);
    master_ = -1;
  }
  if (slave_ >= 0) {
    ::close(slave_);
    slave_ = -1;
  }
}

}  // namespace slamer

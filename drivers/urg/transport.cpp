#include "drivers/urg/transport.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace slamer::urg {

namespace {
constexpr std::array<int, 6> kBauds = {19200, 57600, 115200, 250000, 500000, 750000};

bool set_nonblocking(int fd) {
  const int flags = fcntl(fd, F_GETFL, 0);
  return flags >= 0 && fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

speed_t speed_of(int baud) {
  switch (baud) {
    case 19200:
      return B19200;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 500000:
      return B500000;
    default:
      return B115200;  // 250000 / 750000 have no termios constant: USB models ignore the rate anyway
  }
}
}  // namespace

void Transport::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

bool Transport::read(std::string* bytes, std::string* error) {
  bytes->clear();
  char buffer[8192];
  for (;;) {
    const ssize_t n = ::read(fd_, buffer, sizeof buffer);
    if (n > 0) {
      bytes->append(buffer, static_cast<std::size_t>(n));
      if (static_cast<std::size_t>(n) < sizeof buffer) {
        return true;
      }
      continue;
    }
    if (n == 0) {
      *error = "connection closed by the sensor";
      return false;
    }
    if (errno == EINTR) {
      continue;
    }
    if (errno == EAGAIN || errno == EWOULDBLOCK) {
      return true;
    }
    *error = std::string("read failed: ") + std::strerror(errno);
    return false;
  }
}

bool Transport::write(std::string_view bytes, std::string* error) {
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n < 0 && errno == ENOTSOCK) {
      const ssize_t m = ::write(fd_, bytes.data(), bytes.size());
      if (m >= 0) {
        bytes.remove_prefix(static_cast<std::size_t>(m));
        continue;
      }
    } else if (n >= 0) {
      bytes.remove_prefix(static_cast<std::size_t>(n));
      continue;
    }
    if (errno == EINTR) {
      continue;
    }
    if (errno == EAGAIN || errno == EWOULDBLOCK) {
      pollfd p{fd_, POLLOUT, 0};
      if (poll(&p, 1, 100) <= 0) {
        *error = "write timed out";
        return false;
      }
      continue;
    }
    *error = std::string("write failed: ") + std::strerror(errno);
    return false;
  }
  return true;
}

bool TcpTransport::open(std::string* error) {
  close();
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* result = nullptr;
  const int rc = getaddrinfo(host_.c_str(), std::to_string(port_).c_str(), &hints, &result);
  if (rc != 0 || result == nullptr) {
    *error = "cannot resolve " + host_ + ": " + gai_strerror(rc);
    return false;
  }
  fd_ = socket(result->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0 || !set_nonblocking(fd_)) {
    *error = std::string("socket: ") + std::strerror(errno);
    freeaddrinfo(result);
    close();
    return false;
  }
  const int one = 1;
  setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  const int c = connect(fd_, result->ai_addr, result->ai_addrlen);
  freeaddrinfo(result);
  if (c != 0 && errno != EINPROGRESS) {
    *error = "connect to " + describe() + ": " + std::strerror(errno);
    close();
    return false;
  }
  if (c != 0) {
    pollfd p{fd_, POLLOUT, 0};
    const int ready = poll(&p, 1, static_cast<int>(timeout_s_ * 1000));
    if (ready <= 0) {
      *error = "connect to " + describe() + ": timed out";
      close();
      return false;
    }
    int so_error = 0;
    socklen_t len = sizeof so_error;
    getsockopt(fd_, SOL_SOCKET, SO_ERROR, &so_error, &len);
    if (so_error != 0) {
      *error = "connect to " + describe() + ": " + std::strerror(so_error);
      close();
      return false;
    }
  }
  return true;
}

bool SerialTransport::open(std::string* error) {
  close();
  fd_ = ::open(device_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    *error = "cannot open " + device_ + ": " + std::strerror(errno);
    return false;
  }
  termios tio{};
  if (tcgetattr(fd_, &tio) == 0) {
    cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    cfsetispeed(&tio, speed_of(baud()));
    cfsetospeed(&tio, speed_of(baud()));
    tcsetattr(fd_, TCSANOW, &tio);
    tcflush(fd_, TCIOFLUSH);
  }
  return true;
}

int SerialTransport::baud() const {
  return kBauds[baud_index_ % kBauds.size()];
}

bool SerialTransport::next_baud() {
  baud_index_ = (baud_index_ + 1) % kBauds.size();
  return true;
}

std::string SerialTransport::describe() const {
  return device_ + " @ " + std::to_string(baud()) + " baud";
}

bool FdTransport::open(std::string* error) {
  if (initial_fd_ < 0) {
    *error = name_ + ": closed";
    return false;
  }
  fd_ = initial_fd_;
  initial_fd_ = -1;
  set_nonblocking(fd_);
  return true;
}

}  // namespace slamer::urg

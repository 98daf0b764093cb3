#include "drivers/wheels/device_io.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace slamer {

int open_serial(const std::string& path, std::string* error) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = "cannot open " + path + ": " + std::strerror(errno);
    return -1;
  }
  termios tio{};
  if (tcgetattr(fd, &tio) == 0) {
    cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    cfsetispeed(&tio, B38400);
    cfsetospeed(&tio, B38400);
    tcsetattr(fd, TCSANOW, &tio);
  }
  tcflush(fd, TCIFLUSH);  // input only: never throw away commands not yet sent
  return fd;
}

bool enable_timestamps(int fd) {
  const int on = 1;
  return setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof(on)) == 0;
}

int open_can_socket(const std::string& interface, const std::vector<uint32_t>& ids, bool extended, std::string* error) {
  const int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    *error = std::string("cannot create a CAN socket: ") + std::strerror(errno);
    return -1;
  }
  std::vector<can_filter> filters;
  for (const uint32_t id : ids) {
    filters.push_back(
        {id | (extended ? CAN_EFF_FLAG : 0u), (extended ? CAN_EFF_MASK : CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
  }
  const can_err_mask_t errors = CAN_ERR_MASK;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  sockaddr_can address{};
  address.can_family = AF_CAN;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                 static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0 ||
      setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors)) != 0 || !enable_timestamps(fd) ||
      ioctl(fd, SIOCGIFINDEX, &ifr) != 0) {
    *error = "CAN interface " + interface + ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  address.can_ifindex = ifr.ifr_ifindex;
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    *error = "cannot bind to CAN interface " + interface + ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

ReadResult read_can_frame(int fd, int64_t fallback_utime, can::CanFrame* frame, std::string* error) {
  uint8_t buffer[sizeof(can_frame) + 8];
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval))];
  iovec iov{buffer, sizeof(buffer)};
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  const ssize_t n = recvmsg(fd, &msg, MSG_DONTWAIT);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
      return ReadResult::kWouldBlock;
    }
    *error = std::string("CAN read failed: ") + std::strerror(errno);
    return ReadResult::kError;
  }
  if (n == 0) {
    return ReadResult::kClosed;
  }
  const auto parsed = can::parse_can_frame(std::span<const uint8_t>(buffer, static_cast<std::size_t>(n)));
  if (!parsed || (msg.msg_flags & MSG_TRUNC) != 0) {
    *error = "a CAN datagram of " + std::to_string(n) + " bytes is not a can_frame";
    return ReadResult::kBadSize;
  }
  *frame = *parsed;
  frame->utime = fallback_utime;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMP) {
      timeval tv{};
      std::memcpy(&tv, CMSG_DATA(c), sizeof(tv));
      frame->utime = static_cast<int64_t>(tv.tv_sec) * 1000000 + tv.tv_usec;
    }
  }
  return ReadResult::kFrame;
}

}  // namespace slamer

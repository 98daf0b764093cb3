// The CAN loop: CAN_RAW socket (or unix:PATH SEQPACKET for tests) -> CanOdometry.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "drivers/wheels/backends.hpp"
#include "drivers/wheels/device_io.hpp"
#include "drivers/wheels/wheels_report.hpp"

namespace slamer {

namespace {
int open_transport(const std::string& interface, const std::vector<uint32_t>& ids, bool extended, std::string* error) {
  if (interface.rfind("unix:", 0) != 0) {
    return open_can_socket(interface, ids, extended, error);
  }
  const std::string path = interface.substr(5);
  const int fd = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
  if (fd < 0 || connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    *error = "cannot connect to " + path + ": " + std::strerror(errno);
    if (fd >= 0) {
      ::close(fd);
    }
    return -1;
  }
  enable_timestamps(fd);
  return fd;
}
}  // namespace

int run_can(LcmProcess& process, const WheelsConfig& config) {
  const tfrog::Kinematics kinematics = tfrog::kinematics_from(config.robot);
  CanOdometry odometry(config.can.layout, kinematics);
  const std::string& interface = config.can.interface;
  const bool extended = can::wheel_fields(config.can.layout)[0].extended;
  int fd = -1;
  int64_t next_open = 0;
  int64_t seq = 0;
  int64_t frames = 0;
  int64_t bad = 0;
  std::string last_error;
  process.every(config.poll_period, [&] {
    const int64_t now = now_utime();
    if (fd < 0) {
      if (now < next_open) {
        return;
      }
      std::string error;
      fd = open_transport(interface, odometry.ids(), extended, &error);
      if (fd < 0) {
        if (error != last_error) {
          process.log_warning(error);
        }
        last_error = error;
        next_open = now + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
        return;
      }
      last_error.clear();
      process.log_info("reading CAN frames from " + interface);
    }
    can::CanFrame frame;
    std::string error;
    for (;;) {
      const ReadResult result = read_can_frame(fd, now_utime(), &frame, &error);
      if (result == ReadResult::kWouldBlock) {
        break;
      }
      if (result == ReadResult::kBadSize) {
        ++bad;
        process.count_drop(config.channels.odometry);
        continue;
      }
      if (result != ReadResult::kFrame) {
        process.log_warning(interface + ": " + (result == ReadResult::kClosed ? "closed" : error) + "; reopening");
        ::close(fd);
        fd = -1;
        next_open = now + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
        return;
      }
      ++frames;
      if (const auto sample = odometry.feed(frame)) {
        publish_sample(process, config, kinematics, *sample, "can", &seq);
      }
    }
  });
  int64_t frames_before = 0;
  process.every(config.process.status_period, [&] {
    const double rate = static_cast<double>(frames - frames_before) / config.process.status_period;
    frames_before = frames;
    const bool silent =
        now_utime() - odometry.last_frame_utime() > static_cast<int64_t>(config.can.layout.silence_timeout * 1e6);
    const Report report = can_report(odometry.bus(), rate, fd >= 0, silent, interface);
    process.set_state(report.state, report.message + (bad > 0 ? "; bad datagrams " + std::to_string(bad) : ""));
  });
  const int code = process.run();
  if (fd >= 0) {
    ::close(fd);
  }
  return code;
}

}  // namespace slamer

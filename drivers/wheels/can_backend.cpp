// The CAN loop: CAN_RAW socket (or unix:PATH SEQPACKET for tests) -> CanOdometry.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

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

struct CanLink {
  CanLink(Bus& b, const WheelsConfig& c)
      : bus(b), config(c), kinematics(tfrog::kinematics_from(c.robot)), odometry(c.can.layout, kinematics) {}
  Bus& bus;
  const WheelsConfig& config;
  tfrog::Kinematics kinematics;
  CanOdometry odometry;
  int fd = -1;
  int64_t next_open = 0;
  int64_t seq = 0;
  int64_t frames = 0;
  int64_t bad = 0;
  int64_t frames_before = 0;
  std::string last_error;
};

void start_can(Bus& bus, const WheelsConfig& config) {
  auto s = std::make_shared<CanLink>(bus, config);
  bus.advertise(config.channels.odometry);
  bus.advertise(config.channels.wheel_encoders);
  const std::string& interface = config.can.interface;
  const bool extended = can::wheel_fields(config.can.layout)[0].extended;
  auto read_frames = [s, &bus, &config, interface] {
    can::CanFrame frame;
    std::string error;
    for (;;) {
      const ReadResult result = read_can_frame(s->fd, bus.now(), &frame, &error);
      if (result == ReadResult::kWouldBlock) {
        break;
      }
      if (result == ReadResult::kBadSize) {
        ++s->bad;
        bus.count_drop(config.channels.odometry);
        continue;
      }
      if (result != ReadResult::kFrame) {
        bus.log_warning(interface + ": " + (result == ReadResult::kClosed ? "closed" : error) + "; reopening");
        bus.unwatch(s->fd);
        ::close(s->fd);
        s->fd = -1;
        s->next_open = bus.now() + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
        return;
      }
      ++s->frames;
      if (const auto sample = s->odometry.feed(frame)) {
        publish_sample(bus, config, s->kinematics, *sample, "can", &s->seq);
      }
    }
  };
  bus.every(config.poll_period, [s, &bus, &config, interface, extended, read_frames] {
    const int64_t now = bus.now();
    if (s->fd >= 0 || now < s->next_open) {
      return;
    }
    std::string error;
    s->fd = open_transport(interface, s->odometry.ids(), extended, &error);
    if (s->fd < 0) {
      if (error != s->last_error) {
        bus.log_warning(error);
      }
      s->last_error = error;
      s->next_open = now + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
      return;
    }
    s->last_error.clear();
    bus.log_info("reading CAN frames from " + interface);
    bus.watch(s->fd, read_frames);
  });
  bus.every(config.process.status_period, [s, &bus, &config, interface] {
    const double rate = static_cast<double>(s->frames - s->frames_before) / config.process.status_period;
    s->frames_before = s->frames;
    const bool silent =
        bus.now() - s->odometry.last_frame_utime() > static_cast<int64_t>(config.can.layout.silence_timeout * 1e6);
    const Report report = can_report(s->odometry.bus(), rate, s->fd >= 0, silent, interface);
    bus.set_state(report.state, report.message + (s->bad > 0 ? "; bad datagrams " + std::to_string(s->bad) : ""));
  });
  bus.at_finish([s, &bus] {
    if (s->fd >= 0) {
      bus.unwatch(s->fd);
      ::close(s->fd);
      s->fd = -1;
    }
  });
}

}  // namespace slamer

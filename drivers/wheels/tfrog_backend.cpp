// The T-frog loop: serial port <-> TfrogSession, CMD_VEL in, reopen every reopen_period.
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include "drivers/wheels/backends.hpp"
#include "drivers/wheels/device_io.hpp"
#include "drivers/wheels/wheels_report.hpp"
#include "slamer/velocity_command_t.hpp"

namespace slamer {

namespace {

// The state of one T-frog connection, owned by the bus callbacks.
struct TfrogLink {
  TfrogLink(Bus& b, const WheelsConfig& c) : bus(b), config(c), session(c.tfrog.session, c.robot) {}

  void close_device(const std::string& reason) {
    bus.unwatch(fd);
    ::close(fd);
    fd = -1;
    session.closed(reason);
    next_open = bus.now() + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
    bus.log_warning(config.tfrog.device + ": " + reason + "; reopening every " +
                    std::to_string(config.tfrog.reopen_period) + " s");
  }
  void flush() {
    const auto out = session.take_output();
    std::size_t done = 0;
    while (fd >= 0 && done < out.size()) {
      const ssize_t n = ::write(fd, out.data() + done, out.size() - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
      } else if (n < 0 && errno == EAGAIN) {
        pollfd pfd{fd, POLLOUT, 0};
        if (poll(&pfd, 1, 50) <= 0) {
          close_device("write timed out");
        }
      } else {
        close_device(std::string("write failed: ") + std::strerror(errno));
      }
    }
  }
  void publish() {
    for (const auto& sample : session.take_samples()) {
      publish_sample(bus, config, session.kinematics(), sample, "tfrog", &seq);
    }
  }
  void on_readable() {
    uint8_t buffer[4096];
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof(buffer));
      if (n > 0) {
        session.received(std::span<const uint8_t>(buffer, static_cast<std::size_t>(n)), bus.now());
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
        break;
      }
      close_device(n == 0 ? "device closed" : std::string("read failed: ") + std::strerror(errno));
      return;
    }
    publish();
  }
  void try_open() {
    std::string error;
    fd = open_serial(config.tfrog.device, &error);
    if (fd < 0) {
      if (error != last_open_error) {
        bus.log_warning(error);
      }
      last_open_error = error;
      device_vanished = true;
      next_open = bus.now() + static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
      return;
    }
    last_open_error.clear();
    bus.log_info("opened " + config.tfrog.device);
    session.opened(bus.now(), device_vanished);
    device_vanished = false;
    bus.watch(fd, [this] { on_readable(); });
  }
  void tick() {
    if (fd < 0) {
      if (bus.now() >= next_open) {
        try_open();
      }
      return;
    }
    // Read what is waiting first: after this process was descheduled the
    // frames are in the buffer, and the session must not call that silence.
    on_readable();
    if (fd < 0) {
      return;
    }
    session.tick(bus.now());
    flush();
    publish();
    if (fd >= 0 && session.should_close()) {
      close_device(session.close_reason());
    }
  }
  void report() {
    const auto& status = session.status();
    const double rate = static_cast<double>(status.frames - frames_before) / config.process.status_period;
    frames_before = status.frames;
    const int64_t damaged = status.bad_frames + status.wrong_length;
    if (damaged > damaged_before) {
      bus.count_drop(config.channels.odometry, damaged - damaged_before);
    }
    damaged_before = damaged;
    const Report r = tfrog_report(status, rate, config.tfrog.device);
    bus.set_state(r.state, r.message);
  }
  void finish() {
    if (fd >= 0) {
      session.stop_servos();  // nothing is left moving
      flush();
      if (fd >= 0) {
        tcdrain(fd);
        bus.unwatch(fd);
        ::close(fd);
        fd = -1;
      }
    }
  }

  Bus& bus;
  const WheelsConfig& config;
  tfrog::TfrogSession session;
  int fd = -1;
  int64_t next_open = 0;
  int64_t seq = 0;
  int64_t frames_before = 0;
  int64_t damaged_before = 0;
  std::string last_open_error;
  bool device_vanished = false;  // an open failed since the last close: the board was unplugged
};

}  // namespace

void start_tfrog(Bus& bus, const WheelsConfig& config) {
  auto link = std::make_shared<TfrogLink>(bus, config);
  bus.advertise(config.channels.odometry);
  bus.advertise(config.channels.wheel_encoders);
  bus.subscribe<velocity_command_t>(config.channels.cmd_vel, [link](const velocity_command_t& msg, const ReceiveInfo&) {
    link->session.command(msg.v, msg.omega, link->bus.now());
    link->flush();
  });
  bus.every(config.poll_period, [link] { link->tick(); });
  bus.every(config.process.status_period, [link] { link->report(); });
  bus.at_finish([link] { link->finish(); });
}

}  // namespace slamer

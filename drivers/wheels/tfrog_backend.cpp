// The T-frog loop: serial port <-> TfrogSession, CMD_VEL in, reopen every reopen_period.
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "drivers/wheels/backends.hpp"
#include "drivers/wheels/device_io.hpp"
#include "drivers/wheels/wheels_report.hpp"
#include "slamer/velocity_command_t.hpp"

namespace slamer {

int run_tfrog(LcmProcess& process, const WheelsConfig& config) {
  tfrog::TfrogSession session(config.tfrog.session, config.robot);
  const std::string& device = config.tfrog.device;
  const auto reopen_us = static_cast<int64_t>(config.tfrog.reopen_period * 1e6);
  int fd = -1;
  int64_t next_open = 0;
  int64_t seq = 0;
  std::string last_open_error;
  auto close_device = [&](const std::string& reason) {
    ::close(fd);
    fd = -1;
    session.closed(reason);
    next_open = now_utime() + reopen_us;
    process.log_warning(device + ": " + reason + "; reopening every " + std::to_string(config.tfrog.reopen_period) +
                        " s");
  };
  auto flush = [&] {
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
  };
  process.subscribe<velocity_command_t>(config.channels.cmd_vel,
                                        [&](const velocity_command_t& msg, const ReceiveInfo&) {
                                          session.command(msg.v, msg.omega, now_utime());
                                          flush();
                                        });
  process.every(config.poll_period, [&] {
    int64_t now = now_utime();
    if (fd < 0) {
      if (now < next_open) {
        return;
      }
      std::string error;
      fd = open_serial(device, &error);
      if (fd < 0) {
        if (error != last_open_error) {
          process.log_warning(error);
        }
        last_open_error = error;
        next_open = now + reopen_us;
        return;
      }
      last_open_error.clear();
      process.log_info("opened " + device);
      session.opened(now);
    }
    uint8_t buffer[4096];
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof(buffer));
      if (n > 0) {
        now = now_utime();
        session.received(std::span<const uint8_t>(buffer, static_cast<std::size_t>(n)), now);
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
        break;
      }
      close_device(n == 0 ? "device closed" : std::string("read failed: ") + std::strerror(errno));
      return;
    }
    session.tick(now_utime());
    flush();
    for (const auto& sample : session.take_samples()) {
      publish_sample(process, config, session.kinematics(), sample, "tfrog", &seq);
    }
    if (fd >= 0 && session.should_close()) {
      close_device(session.close_reason());
    }
  });
  int64_t frames_before = 0;
  int64_t damaged_before = 0;
  process.every(config.process.status_period, [&] {
    const auto& status = session.status();
    const double rate = static_cast<double>(status.frames - frames_before) / config.process.status_period;
    frames_before = status.frames;
    const int64_t damaged = status.bad_frames + status.wrong_length;
    if (damaged > damaged_before) {
      process.count_drop(config.channels.odometry, damaged - damaged_before);
    }
    damaged_before = damaged;
    const Report report = tfrog_report(status, rate, device);
    process.set_state(report.state, report.message);
  });
  const int code = process.run();
  if (fd >= 0) {
    session.stop_servos();  // nothing is left moving
    flush();
    if (fd >= 0) {
      tcdrain(fd);
      ::close(fd);
    }
  }
  return code;
}

}  // namespace slamer

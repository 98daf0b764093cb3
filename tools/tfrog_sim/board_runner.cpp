// The board's I/O loop for slamer-tfrog-sim (main.cpp): the pty, unplug and
// replug, one board tick per elapsed millisecond, the wheels turned by a
// scripted path or by wheel_encoders_t from LCM, and one stdout line per
// change: "<utime> servo S0 S1 wref W0 W1", and
// "<utime> unplugged|plugged|watchdog|path-start|path-done X Y THETA DISTANCE FRAMES".
#include "tools/tfrog_sim/board_runner.hpp"

#include <poll.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <optional>

#include "common/process/lcm_bus.hpp"
#include "common/process/stop_signals.hpp"
#include "tools/tfrog_sim/encoder_source.hpp"
#include "tools/tfrog_sim/pty_port.hpp"
#include "tools/tfrog_sim/tfrog_board.hpp"
#include "tools/tfrog_sim/wheel_path.hpp"

namespace slamer::tfrog {
namespace {

constexpr int64_t kMaxCatchUp = 20;  // [ticks]

int64_t monotonic_us() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

}  // namespace

int run_board(const CommandLine& cli) {
  if (!cli.has("link")) {
    throw slamer::CommandLineError("--link PATH is required");
  }
  BoardOptions board_options;
  board_options.protocol = cli.get("protocol");
  const Kinematics kinematics = kinematics_from(RobotParams::from_file(cli.get("robot")));
  std::optional<PathPlayer> path;
  if (cli.has("path")) {
    path.emplace(parse_path(cli.get("path")), kinematics);
  }
  // Before LCM: SIGINT/SIGTERM end the loop below, and the port's destructor removes the link.
  StopSignals stop;
  EncoderFollower follower(kinematics);
  std::optional<EncoderSource> source;
  if (cli.has("source-channel")) {
    source.emplace(cli.get("lcm-url"), cli.get("source-channel"), &follower);
  }
  auto new_board = [&] {
    TfrogBoard board(board_options);
    board.knobs().corrupt_every = static_cast<int>(cli.get_int("corrupt-every"));
    board.knobs().drop_every = static_cast<int>(cli.get_int("drop-every"));
    board.knobs().wrong_length_every = static_cast<int>(cli.get_int("wrong-length-every"));
    board.knobs().error_bits[0] = static_cast<int32_t>(cli.get_int("error-bits"));
    return board;
  };
  TfrogBoard board = new_board();
  slamer::PtyPort port(cli.get("link"));
  port.open();
  std::printf("%ld plugged %s\n", slamer::now_utime(), port.slave_name().c_str());
  std::fflush(stdout);
  const int64_t start = monotonic_us();
  const double unplug_at = cli.get_double("unplug-at");
  const double replug_after = cli.get_double("replug-after");
  const double path_delay = cli.get_double("path-delay");
  const double duration = cli.get_double("duration");
  int64_t board_ticks = 0;
  int64_t streaming_since = -1;
  bool unplugged_once = false;
  int64_t unplugged_at = -1;
  std::string last_state;
  bool was_expired = false;
  uint8_t buffer[4096];
  bool stopping = false;
  while (!stopping && (duration <= 0.0 || monotonic_us() - start < static_cast<int64_t>(duration * 1e6))) {
    const double t = static_cast<double>(monotonic_us() - start) * 1e-6;
    if (port.is_open() && unplug_at >= 0.0 && !unplugged_once && t >= unplug_at) {
      port.close();
      unplugged_once = true;
      unplugged_at = monotonic_us();
      std::printf("%ld unplugged\n", slamer::now_utime());
    } else if (!port.is_open() && monotonic_us() - unplugged_at >= static_cast<int64_t>(replug_after * 1e6)) {
      board = new_board();  // the board resets on USB detach
      port.open();
      std::printf("%ld plugged %s\n", slamer::now_utime(), port.slave_name().c_str());
    }
    pollfd fds[3] = {
        {port.is_open() ? port.fd() : -1, POLLIN, 0}, {source ? source->fd() : -1, POLLIN, 0}, {stop.fd(), POLLIN, 0}};
    if (poll(fds, 3, 1) > 0) {
      stopping = (fds[2].revents & POLLIN) != 0 && stop.requested();
      if ((fds[0].revents & POLLIN) != 0) {
        const ssize_t n = read(port.fd(), buffer, sizeof(buffer));
        if (n > 0) {
          board.receive(std::span<const uint8_t>(buffer, static_cast<std::size_t>(n)));
        }
      }
      if ((fds[1].revents & POLLIN) != 0) {
        source->pump();
      }
    }
    // One board tick per elapsed millisecond.
    // When this process was descheduled, the lost time is skipped, not caught
    // up at once: a burst of ticks without the host bytes that arrived in
    // between would fire the board's watchdog the real board never fires.
    // The path advances only with executed ticks, so counts and truth agree.
    const int64_t due = (monotonic_us() - start) / 1000;
    board_ticks = std::max(board_ticks, due - kMaxCatchUp);
    for (; board_ticks < due; ++board_ticks) {
      const bool streaming = board.servo(0) != 0 || board.servo(1) != 0;
      if (streaming && streaming_since < 0) {
        streaming_since = board_ticks;
      }
      std::array<double, 2> pushed = follower.step();
      if (path && streaming_since >= 0 && board_ticks - streaming_since >= static_cast<int64_t>(path_delay * 1000)) {
        if (!path->done()) {
          if (path->distance() == 0.0) {
            std::printf("%ld path-start\n", slamer::now_utime());
          }
          pushed = path->step(0.001);
          if (path->done()) {
            std::printf("%ld path-done %.9f %.9f %.9f %.6f %ld\n", slamer::now_utime(), path->truth().x,
                        path->truth().y, path->truth().theta, path->distance(), board.frames_sent());
          }
        }
      }
      board.set_pushed(pushed);
      board.step(1);
      const std::string state = "servo " + std::to_string(board.servo(0)) + " " + std::to_string(board.servo(1)) +
                                " wref " + std::to_string(board.w_ref16(0)) + " " + std::to_string(board.w_ref16(1));
      if (state != last_state) {
        std::printf("%ld %s\n", slamer::now_utime(), state.c_str());
        last_state = state;
      }
      if (board.watchdog_expired() && !was_expired) {
        std::printf("%ld watchdog\n", slamer::now_utime());
      }
      was_expired = board.watchdog_expired();
    }
    std::fflush(stdout);
    const auto out = board.take_output();
    if (port.is_open() && !out.empty() && write(port.fd(), out.data(), out.size()) < 0 && errno != EAGAIN) {
      std::fprintf(stderr, "slamer-tfrog-sim: write failed\n");
    }
  }
  return 0;
}

}  // namespace slamer::tfrog

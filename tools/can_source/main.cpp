// slamer-can-source: CAN wheel encoder frames (CANopen TPDO, position actual
// value 0x6064, int32 LE) as real 16-byte can_frames on a unix SEQPACKET socket
// (the driver's --can unix:PATH transport), wheels following --path, with knobs
// for bus-off, garbage datagrams and wrong lengths. Prints "<utime> connected",
// "<utime> bus-off", "<utime> restarted", "<utime> path-done X Y THETA DISTANCE".
#include <linux/can.h>
#include <linux/can/error.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/process/command_line.hpp"
#include "common/process/lcm_bus.hpp"
#include "common/process/process_main.hpp"
#include "common/process/stop_signals.hpp"
#include "tools/tfrog_sim/wheel_path.hpp"

namespace {

void send_frame(int fd, uint32_t id, const uint8_t* data, uint8_t len) {
  can_frame frame{};
  frame.can_id = id;
  frame.len = len;
  std::memcpy(frame.data, data, len);
  (void)send(fd, &frame, sizeof(frame), MSG_NOSIGNAL);
}

int run(const slamer::CommandLine& cli) {
  using namespace slamer::tfrog;
  if (!cli.has("listen")) {
    throw slamer::CommandLineError("--listen PATH is required");
  }
  const Kinematics kinematics = kinematics_from(RobotParams::from_file(cli.get("robot")));
  PathPlayer path(parse_path(cli.get("path")), kinematics);
  const std::string socket_path = cli.get("listen");
  const int listener = socket(AF_UNIX, SOCK_SEQPACKET, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, socket_path.c_str(), sizeof(address.sun_path) - 1);
  ::unlink(socket_path.c_str());
  if (listener < 0 || bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      listen(listener, 1) != 0) {
    throw std::runtime_error("cannot listen on " + socket_path + ": " + std::strerror(errno));
  }
  // SIGINT/SIGTERM end the run, waiting for the driver or streaming, and the socket file is removed.
  slamer::StopSignals stop;
  pollfd waiting[2] = {{listener, POLLIN, 0}, {stop.fd(), POLLIN, 0}};
  while (poll(waiting, 2, -1) < 0 && errno == EINTR) {
  }
  if (stop.requested()) {
    ::close(listener);
    ::unlink(socket_path.c_str());
    return 0;
  }
  const int fd = accept(listener, nullptr, nullptr);
  std::printf("%ld connected\n", slamer::now_utime());
  std::fflush(stdout);
  const double period = 1.0 / cli.get_double("rate");
  const double bus_off_at = cli.get_double("bus-off-at");
  const double bus_off_for = cli.get_double("bus-off-for");
  const int64_t garbage_every = cli.get_int("garbage-every");
  const int64_t short_every = cli.get_int("wrong-length-every");
  const double duration = cli.get_double("duration");
  std::array<double, 2> position{};
  int64_t n = 0;
  bool bus_off_sent = false;
  bool restarted = false;
  bool reported = false;
  for (double t = 0.0; t < duration; t += period, ++n) {
    if (stop.wait(period)) {
      break;
    }
    const double start = cli.get_double("path-delay");
    if (t >= start) {
      const auto counts = path.step(period);
      position[0] += counts[0];
      position[1] += counts[1];
    }
    const bool off = bus_off_at >= 0.0 && t >= bus_off_at && t < bus_off_at + bus_off_for;
    if (off && !bus_off_sent) {
      const uint8_t zeros[8] = {};
      send_frame(fd, CAN_ERR_FLAG | CAN_ERR_BUSOFF, zeros, 8);
      bus_off_sent = true;
      std::printf("%ld bus-off\n", slamer::now_utime());
    }
    if (off) {
      continue;  // nothing on a bus-off bus
    }
    if (bus_off_sent && !restarted) {
      const uint8_t zeros[8] = {};
      send_frame(fd, CAN_ERR_FLAG | CAN_ERR_RESTARTED, zeros, 8);
      restarted = true;
      std::printf("%ld restarted\n", slamer::now_utime());
    }
    if (garbage_every > 0 && n % garbage_every == 0) {
      const char garbage[5] = {'j', 'u', 'n', 'k', '!'};
      (void)send(fd, garbage, sizeof(garbage), MSG_NOSIGNAL);
    }
    for (int m = 0; m < 2; ++m) {
      const auto value =
          static_cast<uint32_t>(static_cast<int32_t>(std::llround(std::floor(position[static_cast<std::size_t>(m)]))));
      const uint8_t data[4] = {static_cast<uint8_t>(value), static_cast<uint8_t>(value >> 8),
                               static_cast<uint8_t>(value >> 16), static_cast<uint8_t>(value >> 24)};
      const bool shorten = short_every > 0 && n % short_every == 0;
      send_frame(fd, static_cast<uint32_t>(0x181 + m), data, shorten ? 2 : 4);
    }
    if (path.done() && !reported) {
      reported = true;
      std::printf("%ld path-done %.9f %.9f %.9f %.6f\n", slamer::now_utime(), path.truth().x, path.truth().y,
                  path.truth().theta, path.distance());
    }
    std::fflush(stdout);
  }
  ::close(fd);
  ::close(listener);
  ::unlink(socket_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-can-source",
      "Serves CANopen wheel encoder frames (nodes 1 = right, 2 = left) on a unix SEQPACKET socket for\n"
      "slamer-wheels --can unix:PATH, with knobs for bus-off, garbage datagrams and wrong lengths.",
      [](slamer::CommandLine& cli) {
        cli.add_option("listen", "PATH", "unix socket to serve");
        cli.add_option("robot", "FILE", "YP-Spur .param file of the robot", "config/robots/icart-mini.param");
        cli.add_option("path", "V,W,T;...", "wheel motion as (v, omega, seconds) segments", "0,0,0");
        cli.add_option("path-delay", "S", "start the path after S seconds", "0.3");
        cli.add_option("rate", "HZ", "frames per second per wheel", "100");
        cli.add_option("bus-off-at", "S", "report bus-off at S seconds (negative: never)", "-1");
        cli.add_option("bus-off-for", "S", "stay bus-off S seconds, then restart", "0.5");
        cli.add_option("garbage-every", "N", "send a 5-byte datagram every N periods", "0");
        cli.add_option("wrong-length-every", "N", "send 2-byte frames every N periods", "0");
        cli.add_option("duration", "S", "exit after S seconds", "10");
      },
      run);
}

#include "tools/urg_sim/sim_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <random>

namespace slamer::urg {

namespace {

int64_t realtime_us() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

int listen_loopback(int port, int* bound_port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only
  addr.sin_port = htons(static_cast<uint16_t>(port));
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || listen(fd, 4) != 0) {
    std::fprintf(stderr, "slamer-urg-sim: cannot listen on 127.0.0.1:%d: %s\n", port, std::strerror(errno));
    close(fd);
    return -1;
  }
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  *bound_port = ntohs(addr.sin_port);
  return fd;
}

class Writer {
 public:
  Writer(int segment_max, unsigned seed) : segment_max_(segment_max), rng_(seed) {}
  bool write(int fd, const std::string& bytes) {
    std::size_t pos = 0;
    while (pos < bytes.size()) {
      std::size_t n = bytes.size() - pos;
      if (segment_max_ > 0) {
        n = std::min<std::size_t>(n, std::uniform_int_distribution<std::size_t>(1, segment_max_)(rng_));
      }
      const ssize_t w = ::write(fd, bytes.data() + pos, n);
      if (w < 0) {
        if (errno == EINTR) {
          continue;
        }
        if (errno == EAGAIN) {
          pollfd p{fd, POLLOUT, 0};
          poll(&p, 1, 50);
          continue;
        }
        return false;
      }
      pos += static_cast<std::size_t>(w);
    }
    return true;
  }

 private:
  int segment_max_;
  std::mt19937 rng_;
};

}  // namespace

int run_sim_server(SimSensor& sensor, const SimServerOptions& o, StopSignals& stop, ScanFeed* feed) {
  std::signal(SIGPIPE, SIG_IGN);
  std::ofstream truth;
  if (!o.truth_file.empty()) {
    truth.open(o.truth_file);
    if (!truth) {
      std::fprintf(stderr, "slamer-urg-sim: cannot write %s\n", o.truth_file.c_str());
      return 1;
    }
    truth << "device_stamp_ms,first_beam_host_us,sent_host_us\n";
  }
  int listen_fd = -1, client = -1, port = o.port;
  if (o.pty) {
    int slave = -1;
    char name[256] = {};
    if (openpty(&client, &slave, name, nullptr, nullptr) != 0) {
      std::fprintf(stderr, "slamer-urg-sim: openpty failed: %s\n", std::strerror(errno));
      return 1;
    }
    termios tio{};
    tcgetattr(slave, &tio);
    cfmakeraw(&tio);
    tcsetattr(slave, TCSANOW, &tio);
    close(slave);  // reopened by the driver through its name
    if (!o.pty_link.empty()) {
      std::filesystem::remove(o.pty_link);
      std::filesystem::create_symlink(name, o.pty_link);
    }
    std::printf("slamer-urg-sim: %s on pty %s\n", sensor.model().name.c_str(), name);
  } else {
    listen_fd = listen_loopback(o.port, &port);
    if (listen_fd < 0) {
      return 1;
    }
    std::printf("slamer-urg-sim: %s on 127.0.0.1:%d\n", sensor.model().name.c_str(), port);
  }
  std::fflush(stdout);
  if (!o.port_file.empty()) {
    std::ofstream(o.port_file + ".tmp") << port << "\n";
    std::filesystem::rename(o.port_file + ".tmp", o.port_file);
  }
  Writer writer(o.segment_max, o.seed);
  const int64_t start = realtime_us();
  sensor.power_on(start);
  int connections = 0;
  int64_t connected_at = 0, down_until = 0;
  bool silent = false;
  bool feed_done = false;
  auto drop = [&](double down_s) {
    if (client >= 0 && !o.pty) {
      close(client);
      client = -1;
    }
    if (down_s > 0 && listen_fd >= 0) {
      close(listen_fd);  // refused while down
      listen_fd = -1;
      down_until = realtime_us() + static_cast<int64_t>(down_s * 1e6);
    }
  };
  char buffer[4096];
  while (!stop.requested()) {
    int64_t now = realtime_us();
    if (o.duration_s > 0 && now - start > static_cast<int64_t>(o.duration_s * 1e6)) {
      break;
    }
    if (listen_fd < 0 && !o.pty && now >= down_until) {
      int again = 0;
      listen_fd = listen_loopback(port, &again);
      if (listen_fd < 0) {
        usleep(100000);
        continue;
      }
    }
    pollfd fds[4];
    int n = 0;
    fds[n++] = {stop.fd(), POLLIN, 0};  // wakes the loop at once for its check above
    const int listen_index = n;
    if (listen_fd >= 0) {
      fds[n++] = {listen_fd, POLLIN, 0};
    }
    const int client_index = n;
    if (client >= 0) {
      fds[n++] = {client, POLLIN, 0};
    }
    const int feed_index = n;
    if (feed != nullptr && feed->fd() >= 0) {
      fds[n++] = {feed->fd(), POLLIN, 0};
    }
    const int64_t next = std::min(sensor.next_event_us(), feed != nullptr ? feed->next_due_us() : INT64_MAX);
    int timeout_ms = 20;
    if (next != INT64_MAX) {
      timeout_ms = static_cast<int>(std::clamp<int64_t>((next - now + 999) / 1000, 0, 20));
    }
    poll(fds, static_cast<nfds_t>(n), timeout_ms);
    now = realtime_us();
    if (listen_fd >= 0 && (fds[listen_index].revents & POLLIN)) {
      const int c = accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (c >= 0) {
        if (client >= 0) {
          close(client);  // one client at a time: the newest wins
        }
        client = c;
        const int one = 1;
        setsockopt(client, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        ++connections;
        connected_at = now;
        silent = false;
      }
    }
    if (client >= 0 && client_index < n && (fds[client_index].revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t r = read(client, buffer, sizeof buffer);
      if (r > 0 && !silent) {
        sensor.receive(std::string_view(buffer, static_cast<std::size_t>(r)), now);
      } else if (r == 0 && !o.pty) {
        close(client);
        client = -1;
      }
    }
    if (feed != nullptr && !feed_done) {
      const bool readable = feed_index < n && (fds[feed_index].revents & POLLIN) != 0;
      feed_done = !feed->pump(sensor, now, readable);
    }
    const std::string out = sensor.poll(now);
    for (const SimTruth& t : sensor.take_truth()) {
      if (truth) {
        truth << t.device_stamp_ms << ',' << t.first_beam_host_us << ',' << t.sent_host_us << '\n';
      }
    }
    if (client >= 0 && connections == 1 && o.silent_after_s >= 0 &&
        now - connected_at > static_cast<int64_t>(o.silent_after_s * 1e6)) {
      silent = true;
    }
    if (client >= 0 && !out.empty() && !silent && !writer.write(client, out) && !o.pty) {
      close(client);
      client = -1;
    }
    if (sensor.reboot_requested()) {
      drop(o.reboot_down_s);
      sensor.power_on(realtime_us() + static_cast<int64_t>(o.reboot_down_s * 1e6));
    }
    if (feed_done && sensor.next_event_us() == INT64_MAX) {
      std::printf("slamer-urg-sim: the scan source has ended\n");
      break;
    }
    if (client >= 0 && connections == 1 && o.drop_after_s >= 0 &&
        now - connected_at > static_cast<int64_t>(o.drop_after_s * 1e6)) {
      connections = 2;  // only the first connection is dropped
      drop(o.down_s);
    }
  }
  if (client >= 0) {
    close(client);
  }
  if (listen_fd >= 0) {
    close(listen_fd);
  }
  if (!o.pty_link.empty()) {
    std::error_code ignored;
    std::filesystem::remove(o.pty_link, ignored);
  }
  return 0;
}

}  // namespace slamer::urg

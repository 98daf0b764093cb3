// What the slamer-launch process tests hear on the bus, and their helpers.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/process/decode.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/support/child_process.hpp"

namespace slamer::test {

using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

inline std::string temp_dir() {
  char pattern[] = "/tmp/slamer_launch_proc_XXXXXX";
  return mkdtemp(pattern);
}

// Alive and not a zombie.
inline bool alive(int64_t pid) {
  const std::string stat = test::read_file("/proc/" + std::to_string(pid) + "/stat");
  const std::size_t close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
}

// What the test hears on the bus.
class Listener {
 public:
  explicit Listener(const std::string& url) : lcm_(url) {
    lcm_.subscribeFunction(
        "PROCESS_STATUS", +[](const lcm::ReceiveBuffer* b, const std::string&, Listener* self) { self->status(b); },
        this);
    lcm_.subscribeFunction(
        "POSE", +[](const lcm::ReceiveBuffer* b, const std::string&, Listener* self) { self->pose(b, false); }, this);
    lcm_.subscribeFunction(
        "GROUND_TRUTH", +[](const lcm::ReceiveBuffer* b, const std::string&, Listener* self) { self->pose(b, true); },
        this);
    lcm_.subscribeFunction(
        "LINE_OBJECTS", +[](const lcm::ReceiveBuffer*, const std::string&, Listener* self) { ++self->line_objects; },
        this);
    lcm_.subscribeFunction(
        "LIDAR",
        +[](const lcm::ReceiveBuffer*, const std::string&, Listener* self) { self->lidar.push_back(since(self->t0)); },
        this);
    lcm_.subscribeFunction(
        "ODOMETRY",
        +[](const lcm::ReceiveBuffer*, const std::string&, Listener* self) {
          self->odometry.push_back(since(self->t0));
        },
        this);
  }
  // Handles messages until `done()` or `timeout_s`; returns done().
  template <class Done>
  bool until(double timeout_s, Done done) {
    const auto start = Clock::now();
    while (!done() && since(start) < timeout_s) {
      lcm_.handleTimeout(20);
    }
    return done();
  }

  struct StatusSeen {
    double at = 0.0;  // the test's time of arrival
    std::string process;
    int32_t pid = 0;
    int8_t state = 0;
    std::string message;
  };
  std::map<std::string, std::set<int32_t>> pids;  // of each process name
  std::vector<StatusSeen> statuses;
  std::vector<std::pair<double, pose_estimate_t>> poses;  // with the test's time of arrival
  std::vector<pose_estimate_t> truth;
  int line_objects = 0;
  std::vector<double> lidar, odometry;  // arrival times
  Clock::time_point t0 = Clock::now();

 private:
  void status(const lcm::ReceiveBuffer* b) {
    process_status_t m{};
    if (decode_message(b->data, b->data_size, &m) == DecodeStatus::kOk) {
      pids[m.process].insert(m.pid);
      statuses.push_back({since(t0), m.process, m.pid, m.state, m.message});
    }
  }
  void pose(const lcm::ReceiveBuffer* b, bool is_truth) {
    pose_estimate_t m{};
    if (decode_message(b->data, b->data_size, &m) == DecodeStatus::kOk) {
      if (is_truth) {
        truth.push_back(m);
      } else {
        poses.emplace_back(since(t0), m);
      }
    }
  }
  lcm::LCM lcm_;
};

// Against the truth nearest in time (the truth arrives in utime order).
inline double error_to_truth(const pose_estimate_t& p, const std::vector<pose_estimate_t>& truth) {
  const auto after = std::lower_bound(truth.begin(), truth.end(), p.utime,
                                      [](const pose_estimate_t& t, int64_t utime) { return t.utime < utime; });
  const pose_estimate_t* best = nullptr;
  for (auto it = after == truth.begin() ? after : after - 1; it != truth.end() && it <= after; ++it) {
    if (best == nullptr || std::llabs(it->utime - p.utime) < std::llabs(best->utime - p.utime)) {
      best = &*it;
    }
  }
  return best == nullptr ? 1e9 : std::hypot(p.x - best->x, p.y - best->y);
}

inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

// The first message at or after `t`; -1 if none.
inline double first_after(const std::vector<double>& times, double t) {
  for (const double x : times) {
    if (x >= t) {
      return x;
    }
  }
  return -1.0;
}

inline int free_tcp_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  bind(fd, reinterpret_cast<sockaddr*>(&address), size);
  getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  close(fd);
  return ntohs(address.sin_port);
}

inline int64_t supervisord_pid(const std::string& launch_stderr) {
  const std::size_t at = launch_stderr.find("supervisord ");
  return at == std::string::npos ? 0 : std::atoll(launch_stderr.c_str() + at + 12);
}

}  // namespace slamer::test

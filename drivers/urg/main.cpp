// slamer-urg: a Hokuyo URG (SCIP 2.0 over TCP or serial) -> laser_scan_t on LIDAR.
// The sensor I/O runs on its own thread (bytes are timestamped as they arrive,
// whatever the bus is doing) and wakes the bus through an eventfd when it has
// scans; the bus (live LCM) publishes them, and PROCESS_STATUS from its timers.
#include <sys/eventfd.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "common/process/bus.hpp"
#include "common/process/convert.hpp"
#include "common/process/process_main.hpp"
#include "drivers/urg/urg_driver.hpp"
#include "drivers/urg/urg_options.hpp"
#include "slamer/laser_scan_t.hpp"

namespace slamer::urg {
namespace {

std::string describe(const UrgDriverStatus& s, double rate_hz) {
  char line[512];
  const SessionCounters& c = s.counters;
  std::snprintf(
      line, sizeof line,
      "%s %s serial %s at %s: %s, %.1f Hz; refused scans checksum %lld truncated %lld length %lld "
      "bad_char %lld; malfunctions %lld resets %lld reboots %lld timeouts %lld silences %lld; "
      "reconnects %lld; time sync %s width %.0f us drift %.1f ppm",
      s.streaming ? "streaming" : s.state.c_str(), s.model.empty() ? "?" : s.model.c_str(),
      s.serial.empty() ? "?" : s.serial.c_str(), s.where.c_str(), s.connected ? "connected" : "disconnected", rate_hz,
      static_cast<long long>(c.checksum), static_cast<long long>(c.truncated), static_cast<long long>(c.length),
      static_cast<long long>(c.bad_char), static_cast<long long>(c.malfunctions), static_cast<long long>(c.resets),
      static_cast<long long>(c.reboots), static_cast<long long>(c.timeouts), static_cast<long long>(c.silences),
      static_cast<long long>(s.reconnects), s.synced ? "ok" : "none", s.sync_width_us, s.drift_ppm);
  std::string text = line;
  if (!s.streaming && !s.last_error.empty()) {
    text += "; last error: " + s.last_error;
  }
  return text;
}

int run(const UrgProcessConfig& config, const CommandLine& cli) {
  const std::unique_ptr<Bus> bus = open_bus(cli, "slamer-urg", config.process);
  Bus& process = *bus;
  process.advertise(config.lidar_channel);
  std::mutex mutex;
  std::vector<LaserScan> queue;
  UrgDriverStatus status;
  std::atomic<bool> stop{false};
  const int wake = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake < 0) {
    throw std::runtime_error("cannot create an eventfd");
  }
  std::thread io([&] {
    UrgDriver driver(config);
    int64_t status_at = 0;
    while (!stop) {
      driver.step(10);
      std::vector<LaserScan> scans = driver.take_scans();
      const int64_t now = host_now_us();
      std::lock_guard<std::mutex> lock(mutex);
      for (auto& s : scans) {
        queue.push_back(std::move(s));
      }
      if (!scans.empty() || now - status_at >= 50000) {  // the status copy allocates: 20 Hz is plenty
        status = driver.status();
        status_at = now;
      }
      if (!scans.empty()) {
        const uint64_t one = 1;
        (void)!write(wake, &one, sizeof one);
      }
    }
  });
  process.watch(wake, [&] {
    uint64_t count = 0;
    (void)!read(wake, &count, sizeof count);
    std::vector<LaserScan> scans;
    {
      std::lock_guard<std::mutex> lock(mutex);
      scans.swap(queue);
    }
    for (const LaserScan& s : scans) {
      process.publish(config.lidar_channel, to_message(s));
    }
  });
  int64_t last_scans = 0, last_refused = 0, last_scans_ok = 0;
  int64_t last_time = host_now_us();
  // The state is refreshed 4x per PROCESS_STATUS so it is never a second stale.
  process.every(0.25, [&] {
    UrgDriverStatus s;
    {
      std::lock_guard<std::mutex> lock(mutex);
      s = status;
    }
    const int64_t now = process.now();
    const double rate = static_cast<double>(s.counters.scans - last_scans) * 1e6 / static_cast<double>(now - last_time);
    const int64_t refused = s.counters.checksum + s.counters.truncated + s.counters.length + s.counters.bad_char;
    if (refused > last_refused) {
      process.count_drop(config.lidar_channel, refused - last_refused);
    }
    last_scans = s.counters.scans, last_refused = refused, last_time = now;
    const bool ok = s.streaming && s.counters.scans > last_scans_ok;
    last_scans_ok = s.counters.scans;
    process.set_state(ok ? process_status_t::OK : process_status_t::DEGRADED, describe(s, rate));
  });
  process.set_state(process_status_t::DEGRADED, "starting: no sensor yet");
  const int code = process.run();
  stop = true;
  io.join();
  close(wake);
  return code;
}

}  // namespace
}  // namespace slamer::urg

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-urg",
      "Reads a Hokuyo URG sensor (SCIP 2.0 over TCP or serial/USB; a SCIP 1.1 URG-04LX is switched to\n"
      "2.0) and publishes every scan once as laser_scan_t on LIDAR, with utime the host time of the\n"
      "first beam from a model of the sensor's clock. Reconnects forever.",
      [](slamer::CommandLine& cli) {
        cli.add_option("host", "HOST", "sensor address (overrides connection.host)");
        cli.add_option("port", "PORT", "sensor TCP port (overrides connection.port)");
        cli.add_option("device", "PATH", "serial/USB device instead of TCP (overrides connection.device)");
      },
      [](const slamer::CommandLine& cli) {
        auto config = slamer::load_config<slamer::urg::UrgProcessConfig>(cli);
        if (cli.has("host")) {
          config.connection.host = cli.get("host");
        }
        if (cli.has("port")) {
          const int64_t port = cli.get_int("port");
          if (port < 1 || port > 65535) {
            throw slamer::CommandLineError("--port: must be in [1, 65535]");
          }
          config.connection.port = static_cast<int>(port);
        }
        if (cli.has("device")) {
          config.connection.device = cli.get("device");
        }
        return slamer::urg::run(config, cli);
      });
}

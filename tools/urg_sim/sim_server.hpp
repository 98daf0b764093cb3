// The I/O side of slamer-urg-sim: serves one SimSensor on loopback TCP (one
// client at a time, like the real sensor) or on a pty, with the transport
// knobs (segmenting, dropped connections, silence, reboot downtime) and the
// truth file (device stamp, true host time of each scan's first beam).
#pragma once

#include <cstdint>
#include <string>

#include "common/process/stop_signals.hpp"
#include "tools/urg_sim/sim_sensor.hpp"

namespace slamer::urg {

struct SimServerOptions {
  int port = 0;                // 0: a free port
  std::string port_file;       // the port written here once listening
  bool pty = false;            // serve on a pty instead of TCP
  std::string pty_link;        // a symlink to the pty's slave
  int segment_max = 0;         // > 0: replies written in random pieces of 1..segment_max bytes
  double drop_after_s = -1;    // close the first connection after this long
  double down_s = 0;           // refuse connections this long after a drop
  double silent_after_s = -1;  // the first connection goes silent (stays open) after this long
  double reboot_down_s = 0.5;  // unreachable this long after an RB pair
  std::string truth_file;      // CSV: device_stamp_ms,first_beam_host_us,sent_host_us
  double duration_s = 0;       // 0: until SIGINT/SIGTERM
  unsigned seed = 1;
};

// Scans from outside (scan_feed.hpp), polled in the server's loop.
class ScanFeed {
 public:
  virtual ~ScanFeed() = default;
  virtual int fd() const { return -1; }  // readable when scans may have arrived; -1: none
  // Hands the sensor what has arrived or is due by `host_us`; false once the source has ended.
  virtual bool pump(SimSensor& sensor, int64_t host_us, bool readable) = 0;
  virtual int64_t next_due_us() const { return INT64_MAX; }  // host time it needs pumping again
};

// Runs until the duration ends, `stop` is requested (SIGINT/SIGTERM), or the
// feed has ended and its last scan is sent; removes options.pty_link; returns
// the exit code.
int run_sim_server(SimSensor& sensor, const SimServerOptions& options, StopSignals& stop, ScanFeed* feed = nullptr);

}  // namespace slamer::urg

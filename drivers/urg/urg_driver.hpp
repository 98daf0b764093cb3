// The I/O around one UrgSession for slamer-urg: opens the transport (TCP or
// serial), retries with a backoff doubling from 0.1 s up to max_backoff,
// timestamps arriving bytes with the host clock, moves the session's bytes and
// scans, probes the next baud rate when a serial sensor never answers. Never
// gives up. Owned and called by one thread.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/sensors/laser_scan.hpp"
#include "drivers/urg/transport.hpp"
#include "drivers/urg/urg_options.hpp"
#include "drivers/urg/urg_session.hpp"

namespace slamer::urg {

int64_t host_now_us();  // CLOCK_REALTIME [us since the Unix epoch]

struct UrgDriverStatus {
  bool connected = false;
  bool streaming = false;
  std::string where;  // host:port or device
  std::string state;  // session state
  std::string model, serial;
  std::string last_error;  // one line
  SessionCounters counters;
  int64_t reconnects = 0;
  double sync_width_us = 0, drift_ppm = 0;
  bool synced = false;
};

class UrgDriver {
 public:
  explicit UrgDriver(const UrgProcessConfig& config);
  // One step: waits up to timeout_ms for bytes, then does what is due.
  void step(int timeout_ms);
  std::vector<LaserScan> take_scans() { return session_.take_scans(); }
  UrgDriverStatus status() const;

 private:
  void try_connect(int64_t now);
  void drop(const std::string& why, int64_t now);
  void flush(int64_t now);

  UrgProcessConfig config_;
  std::unique_ptr<Transport> transport_;
  UrgSession session_;
  int64_t next_attempt_us_ = 0;
  double backoff_s_ = 0.1;
  int64_t reconnects_ = 0;
  bool ever_connected_ = false;
  std::string last_error_;
};

}  // namespace slamer::urg

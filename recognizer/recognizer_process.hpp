// The one wiring of slamer-recognizer, whatever the bus (bus.hpp): each
// usable LIDAR scan in, its LINE_OBJECTS out.
//   A scan is refused (counted as a drop of LIDAR, the reason summarized in
//   the log) if it has more beams than max_beams or intensities that do not
//   match its ranges; stale scans (stream_order.hpp) are dropped too.
//   Scans the sequence numbers say were lost before they reached us are
//   "missed", not drops (we never had them): counted apart, and only as many
//   as the time between the scans allows, so one bogus seq cannot add thousands.
//   No scan for scan_timeout: PROCESS_STATUS degraded.
#pragma once

#include <cstdint>
#include <string>

#include "common/process/bus.hpp"
#include "common/process/stream_order.hpp"
#include "recognizer/line_recognizer.hpp"
#include "recognizer/recognizer_config.hpp"
#include "slamer/laser_scan_t.hpp"

namespace slamer {

// Why a decoded scan cannot be used, or "" if it can.
std::string check_scan(const laser_scan_t& scan, int max_beams);

// Scans missed between two in-order scans: the seq gap, bounded by the time
// between them over the scan period (no bound without a scan period).
int64_t missed_scans(int64_t last_seq, int64_t last_utime, const laser_scan_t& scan);

class RecognizerProcess {
 public:
  RecognizerProcess(Bus& bus, const RecognizerProcessConfig& config);
  // The bus holds callbacks that point at this object: it stays where it was made.
  RecognizerProcess(const RecognizerProcess&) = delete;
  RecognizerProcess& operator=(const RecognizerProcess&) = delete;

  int64_t scans_recognized() const { return recognized_; }
  int64_t scans_missed() const { return missed_; }

 private:
  void on_scan(const laser_scan_t& scan);

  Bus& bus_;
  RecognizerProcessConfig config_;
  LineRecognizer recognizer_;
  StreamOrder order_;
  int64_t last_seq_ = -1;
  int64_t last_utime_ = 0;
  int64_t last_arrival_ = 0;
  int64_t recognized_ = 0;
  int64_t missed_ = 0;
};

}  // namespace slamer

// Where slamer-urg-sim's scans come from when not from its fixed scene: live
// laser_scan_t messages on an LCM channel (--source-channel, e.g. slamer-sim's
// SIM_LIDAR) or the scans of an LCM log played at their own pace
// (--source-log). Each scan goes through sim_scan_from() (the model's
// geometry, SCIP error codes); scans that do not fit are dropped with a
// one-line reason (first one, then a count at most every 5 s).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "common/process/event_log.hpp"
#include "tools/urg_sim/sim_server.hpp"

namespace slamer::urg {

class FeedProblems {
 public:
  explicit FeedProblems(std::string what) : what_(std::move(what)) {}
  void report(const std::string& reason, int64_t host_us);

 private:
  std::string what_;
  int64_t count_ = 0;
  int64_t last_log_us_ = 0;
};

// Live scans from LCM. Throws std::runtime_error if LCM cannot be opened.
class LcmScanFeed final : public ScanFeed {
 public:
  LcmScanFeed(const std::string& lcm_url, const std::string& channel);
  int fd() const override { return fd_; }
  bool pump(SimSensor& sensor, int64_t host_us, bool readable) override;

 private:
  static void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel, LcmScanFeed* self);
  lcm::LCM lcm_;
  int fd_ = -1;
  SimSensor* sensor_ = nullptr;
  int64_t now_us_ = 0;
  FeedProblems problems_;
};

// The scans on `channel` of a log, their first beams shifted so the first one
// is measured when the driver starts streaming, the others at the log's pace.
class LogScanFeed final : public ScanFeed {
 public:
  LogScanFeed(const std::string& path, const std::string& channel);  // throws std::runtime_error
  bool pump(SimSensor& sensor, int64_t host_us, bool readable) override;
  int64_t next_due_us() const override;

 private:
  bool load_next(const SimModel& model, int64_t host_us);  // false at the end of the log

  EventLogReader reader_;
  std::string channel_;
  std::optional<SimScan> next_;
  bool anchored_ = false;
  int64_t shift_us_ = 0;
  FeedProblems problems_;
};

}  // namespace slamer::urg

// End-to-end latency of a recorded live run (issue 15), from an lcm-logger log.
//
// A scan's utime is the host time of its first beam (the URG driver's
// estimate from the sensor's clock). The logger stamps each event when it
// received it, on the same host, so "bus time - utime" is how long after the
// first beam a message was on the bus: for LIDAR (the sensor's sweep, its
// transfer and the driver), LINE_OBJECTS (+ the recognizer) and POSE (+ the
// localizer). The sweep itself (first to last beam: 18.75 ms for 270 deg at
// 40 Hz) no software can shorten, so the POSE latency after the last beam is
// given as well. Messages are matched to their scan by utime; scans whose seq
// skips a number were lost before the bus (by the sensor or the driver).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace slamer {

struct LatencyStats {
  int64_t count = 0;
  double p50_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
};

// The last PROCESS_STATUS of a process in the log.
struct ProcessTotals {
  std::string process;
  int pids = 0;  // > 1: it was restarted during the run (totals are summed over them)
  int64_t messages_in = 0;
  int64_t messages_out = 0;
  int64_t decode_errors = 0;
  int64_t drops = 0;
  double processing_p99_ms = 0.0;  // the largest of its runs'
};

struct LatencyReport {
  double duration_s = 0.0;  // first to last scan
  int64_t scans = 0;
  int64_t scans_lost_before_bus = 0;  // seq numbers skipped
  int64_t scans_without_objects = 0;
  int64_t scans_without_pose = 0;
  int64_t unmatched_objects = 0;  // for no scan in the log (e.g. the log started mid-run)
  int64_t unmatched_poses = 0;
  LatencyStats lidar;                    // first beam -> LIDAR on the bus
  LatencyStats objects;                  // first beam -> LINE_OBJECTS on the bus
  LatencyStats pose;                     // first beam -> POSE on the bus (end to end)
  LatencyStats pose_after_last_beam;     // last beam -> POSE on the bus
  std::vector<ProcessTotals> processes;  // by name
};

class LatencyRecorder {
 public:
  void on_scan(int64_t utime, int64_t seq, double sweep_s, int64_t bus_utime);
  void on_objects(int64_t scan_utime, int64_t bus_utime);
  void on_pose(int64_t scan_utime, int64_t bus_utime);
  void on_status(const std::string& process, int32_t pid, const ProcessTotals& totals);

  LatencyReport report() const;

 private:
  struct Scan {
    int64_t utime = 0;
    double sweep_s = 0.0;
    int64_t lidar_bus = 0;
    std::optional<int64_t> objects_bus;
    std::optional<int64_t> pose_bus;
  };
  std::vector<Scan> scans_;
  std::unordered_map<int64_t, std::size_t> by_utime_;
  std::optional<int64_t> last_seq_;
  int64_t seq_skipped_ = 0;
  int64_t unmatched_objects_ = 0;
  int64_t unmatched_poses_ = 0;
  std::map<std::string, std::map<int32_t, ProcessTotals>> statuses_;
};

std::string render_text(const LatencyReport& report);
std::string render_json(const LatencyReport& report);

}  // namespace slamer

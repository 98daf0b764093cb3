#include "recognizer/recognizer_process.hpp"

#include <algorithm>
#include <cmath>

#include "common/process/convert.hpp"
#include "slamer/line_objects_t.hpp"

namespace slamer {

std::string check_scan(const laser_scan_t& scan, int max_beams) {
  if (scan.nranges > max_beams) {
    return std::to_string(scan.nranges) + " beams (more than max_beams " + std::to_string(max_beams) + ")";
  }
  if (scan.nintensities != 0 && scan.nintensities != scan.nranges) {
    return "intensities do not match the ranges";
  }
  return "";
}

int64_t missed_scans(int64_t last_seq, int64_t last_utime, const laser_scan_t& scan) {
  if (last_seq < 0 || scan.seq <= last_seq + 1) {
    return 0;
  }
  int64_t missed = scan.seq - last_seq - 1;
  if (std::isfinite(scan.scan_period) && scan.scan_period > 0.0) {
    const double periods = static_cast<double>(scan.utime - last_utime) * 1e-6 / scan.scan_period;
    missed = std::min<int64_t>(missed, std::max<int64_t>(0, std::llround(periods) - 1));
  }
  return missed;
}

RecognizerProcess::RecognizerProcess(Bus& bus, const RecognizerProcessConfig& config)
    : bus_(bus), config_(config), recognizer_(config.recognizer), last_arrival_(bus.now()) {
  bus_.subscribe<laser_scan_t>(
      config_.lidar_channel,
      [this](const laser_scan_t& scan, const ReceiveInfo& info) {
        last_arrival_ = info.receive_utime;
        on_scan(scan);
      },
      true);
  bus_.advertise(config_.line_objects_channel);
  bus_.every(1.0, [this] {
    if (bus_.now() - last_arrival_ > static_cast<int64_t>(config_.scan_timeout * 1e6)) {
      bus_.set_state(process_status_t::DEGRADED, "no scans on " + config_.lidar_channel + " for " +
                                                     std::to_string(static_cast<int>(config_.scan_timeout)) + " s");
    }
  });
}

void RecognizerProcess::on_scan(const laser_scan_t& scan) {
  if (const std::string problem = check_scan(scan, config_.max_beams); !problem.empty()) {
    bus_.count_drop(config_.lidar_channel);
    bus_.count_error(config_.lidar_channel + ": " + problem);
    return;
  }
  const Arrival arrival = order_.check(scan.utime);
  if (arrival == Arrival::kStale) {
    bus_.count_drop(config_.lidar_channel);
    return;
  }
  if (arrival == Arrival::kInOrder) {
    missed_ += missed_scans(last_seq_, last_utime_, scan);
  }
  last_seq_ = scan.seq;
  last_utime_ = scan.utime;
  bus_.publish(config_.line_objects_channel,
               to_line_objects_message(recognizer_.recognize(from_message(scan)), scan.frame));
  ++recognized_;
  bus_.set_state(process_status_t::OK, missed_ > 0 ? std::to_string(missed_) + " scans missed (gaps in seq)" : "");
}

}  // namespace slamer

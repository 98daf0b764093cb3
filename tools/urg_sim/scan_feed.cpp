#include "tools/urg_sim/scan_feed.hpp"

#include <cstdio>
#include <stdexcept>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/lcm_bus.hpp"
#include "slamer/laser_scan_t.hpp"
#include "tools/urg_sim/sim_scan_source.hpp"

namespace slamer::urg {

void FeedProblems::report(const std::string& reason, int64_t host_us) {
  ++count_;
  if (count_ == 1 || host_us - last_log_us_ >= 5000000) {
    std::fprintf(stderr, "slamer-urg-sim: %s: scan dropped (%lld so far): %s\n", what_.c_str(),
                 static_cast<long long>(count_), reason.c_str());
    last_log_us_ = host_us;
  }
}

namespace {

// Decodes and converts one laser_scan_t; false with `reason` if it cannot be used.
bool convert(const void* data, std::size_t size, const SimModel& model, int64_t host_us, SimScan* scan,
             std::string* reason) {
  laser_scan_t message;
  const DecodeStatus status = decode_message(data, size, &message);
  if (status != DecodeStatus::kOk) {
    *reason = "not a laser_scan_t (" + std::string(describe(status)) + ")";
    return false;
  }
  return sim_scan_from(from_message(message), model, host_us, scan, reason);
}

}  // namespace

LcmScanFeed::LcmScanFeed(const std::string& lcm_url, const std::string& channel) : lcm_(lcm_url), problems_(channel) {
  if (!lcm_.good()) {
    throw std::runtime_error("cannot open LCM" + (lcm_url.empty() ? std::string() : " URL '" + lcm_url + "'"));
  }
  lcm_.subscribeFunction(literal_pattern(channel), &LcmScanFeed::on_message, this);
  fd_ = lcm_.getFileno();
}

void LcmScanFeed::on_message(const lcm::ReceiveBuffer* buffer, const std::string&, LcmScanFeed* self) {
  SimScan scan;
  std::string reason;
  if (convert(buffer->data, buffer->data_size, self->sensor_->model(), self->now_us_, &scan, &reason)) {
    self->sensor_->feed(std::move(scan));
  } else {
    self->problems_.report(reason, self->now_us_);
  }
}

bool LcmScanFeed::pump(SimSensor& sensor, int64_t host_us, bool readable) {
  sensor_ = &sensor;
  now_us_ = host_us;
  if (readable) {
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  return true;
}

LogScanFeed::LogScanFeed(const std::string& path, const std::string& channel)
    : reader_(path), channel_(channel), problems_(path + " " + channel) {}

bool LogScanFeed::load_next(const SimModel& model, int64_t host_us) {
  while (const std::optional<LogEvent> event = reader_.next()) {
    if (event->channel != channel_) {
      continue;
    }
    SimScan scan;
    std::string reason;
    if (convert(event->data.data(), event->data.size(), model, host_us, &scan, &reason)) {
      next_ = std::move(scan);
      return true;
    }
    problems_.report(reason, host_us);
  }
  if (!reader_.problems().empty()) {
    std::fprintf(stderr, "slamer-urg-sim: %s\n", reader_.problems().c_str());
  }
  return false;
}

int64_t LogScanFeed::next_due_us() const {
  return next_ && anchored_ ? next_->first_beam_us + shift_us_ : INT64_MAX;
}

bool LogScanFeed::pump(SimSensor& sensor, int64_t host_us, bool) {
  if (!next_ && !load_next(sensor.model(), host_us)) {
    return false;
  }
  if (!anchored_) {
    if (!sensor.scanning()) {
      return true;  // the log starts when the driver starts streaming
    }
    anchored_ = true;
    shift_us_ = host_us - next_->first_beam_us;
  }
  while (next_ && next_->first_beam_us + shift_us_ <= host_us) {
    SimScan scan = std::move(*next_);
    next_.reset();
    scan.first_beam_us += shift_us_;
    scan.received_us = host_us;
    sensor.feed(std::move(scan));
    if (!load_next(sensor.model(), host_us)) {
      return false;
    }
  }
  return true;
}

}  // namespace slamer::urg

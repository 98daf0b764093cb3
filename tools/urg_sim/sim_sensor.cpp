#include "tools/urg_sim/sim_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "drivers/urg/scip_codec.hpp"

namespace slamer::urg {

bool sim_model(const std::string& name, SimModel* m) {
  *m = SimModel{};
  m->name = name;
  if (name == "URM-40LC") {
    m->name = "URM-40LC-EW";
    m->dmin = 60, m->dmax = 30000, m->ares = 1440, m->amin = 0, m->amax = 1080, m->afrt = 540, m->scan_rpm = 2400;
  } else if (name == "UST-10LX") {
    m->dmin = 20, m->dmax = 30000, m->ares = 1440, m->amin = 0, m->amax = 1080, m->afrt = 540, m->scan_rpm = 2400;
    m->tm_on_5ms_ticks = true;
  } else if (name == "UTM-30LX") {
    m->dmin = 23, m->dmax = 60000, m->ares = 1440, m->amin = 0, m->amax = 1080, m->afrt = 540, m->scan_rpm = 2400;
  } else if (name == "URG-04LX") {
    m->dmin = 20, m->dmax = 5600, m->ares = 1024, m->amin = 44, m->amax = 725, m->afrt = 384, m->scan_rpm = 600;
    m->scip1_at_power_up = true;
    m->intensities = false;
  } else {
    return false;
  }
  return true;
}

SimSensor::SimSensor(SimModel model, SimKnobs knobs)
    : model_(std::move(model)), model_after_reboot_(model_), knobs_(std::move(knobs)), rng_(knobs_.seed) {
  if (!knobs_.model_after_reboot.empty()) {
    sim_model(knobs_.model_after_reboot, &model_after_reboot_);
  }
}

void SimSensor::power_on(int64_t host_us) {
  state_ = State::kIdle;
  scip1_ = model_.scip1_at_power_up;
  laser_on_ = false;
  power_on_us_ = host_us;
  input_.clear();
  out_.clear();
  last_due_us_ = host_us;
  rb_count_ = 0;
  reboot_ = false;
  error_latched_ = false;
  scans_total_ = 0;
  fed_.clear();
}

double SimSensor::device_ms(int64_t host_us) const {
  return knobs_.offset_ms + (1.0 + knobs_.drift_ppm * 1e-6) * static_cast<double>(host_us - power_on_us_) / 1000.0;
}

void SimSensor::reply(int64_t ready_us, const std::string& bytes) {
  double delay_us = knobs_.delay_ms * 1000.0;
  if (knobs_.jitter_ms > 0) {
    delay_us += std::uniform_real_distribution<double>(0.0, knobs_.jitter_ms * 1000.0)(rng_);
  }
  // One byte stream: replies arrive in order.
  const int64_t due = std::max(last_due_us_, ready_us + static_cast<int64_t>(delay_us));
  last_due_us_ = due;
  out_.push_back({due, bytes});
}

std::string SimSensor::status_reply(const std::string& echo, const std::string& status, const std::string& body) {
  return echo + "\n" + status + scip_checksum(status) + "\n" + body + "\n";
}

std::string SimSensor::kv(const std::string& key, const std::string& value) const {
  const std::string text = key + ":" + value;
  return text + ";" + scip_checksum(text) + "\n";  // ';' not summed, as real devices do
}

void SimSensor::receive(std::string_view bytes, int64_t host_us) {
  input_.append(bytes);
  std::size_t lf;
  while ((lf = input_.find_first_of("\r\n")) != std::string::npos) {
    std::string line = input_.substr(0, lf);
    std::size_t next = lf + 1;
    if (input_[lf] == '\r' && next < input_.size() && input_[next] == '\n') {
      ++next;
    }
    input_.erase(0, next);
    if (!line.empty()) {
      command(line, host_us);
    }
  }
  if (input_.size() > 4096) {
    input_.clear();
  }
}

void SimSensor::command(const std::string& line, int64_t now) {
  const std::string head = line.substr(0, line.find(';'));
  if (scip1_) {
    // SCIP 1.1: one-char status, no checksums; only the switch to 2.0 is understood.
    if (head == "SCIP2.0") {
      scip1_ = false;
      reply(now, line + "\n0\n\n");
    } else {
      reply(now, line + "\nE\n\n");
    }
    return;
  }
  if (state_ == State::kTimeAdjust && head.rfind("TM", 0) != 0) {
    reply(now, status_reply(line, "0E"));
    return;
  }
  if (head == "QT") {
    if (state_ == State::kScanning) {
      state_ = State::kIdle;
    }
    laser_on_ = false;
    reply(now, status_reply(line, "00"));
  } else if (head == "VV") {
    reply(now,
          status_reply(line, "00",
                       kv("VEND", "Hokuyo Automatic Co.,Ltd.") + kv("PROD", model_.name) +
                           kv("FIRM", "1.0.0(slamer-urg-sim)") + kv("PROT", "SCIP 2.0") + kv("SERI", model_.serial)));
  } else if (head == "PP") {
    reply(now, status_reply(line, "00",
                            kv("MODL", model_.name) + kv("DMIN", std::to_string(model_.dmin)) +
                                kv("DMAX", std::to_string(model_.dmax)) + kv("ARES", std::to_string(model_.ares)) +
                                kv("AMIN", std::to_string(model_.amin)) + kv("AMAX", std::to_string(model_.amax)) +
                                kv("AFRT", std::to_string(model_.afrt)) + kv("SCAN", std::to_string(model_.scan_rpm))));
  } else if (head == "II") {
    const uint32_t stamp = static_cast<uint32_t>(std::floor(device_ms(now))) & 0xFFFFFFu;
    reply(now, status_reply(line, error_latched_ ? "0L" : "00",
                            kv("MODL", model_.name) + kv("LASR", laser_on_ ? "ON" : "OFF") +
                                kv("SCSP", std::to_string(model_.scan_rpm)) + kv("MESM", "Measuring mode") +
                                kv("SBPS", "Ethernet 100 [Mbps]") + kv("TIME", scip_encode(stamp, 4)) +
                                kv("STAT", error_latched_ ? "Laser malfunction" : "Sensor works well.")));
  } else if (head == "BM") {
    if (error_latched_) {
      reply(now, status_reply(line, "01"));
      return;
    }
    reply(now, status_reply(line, laser_on_ ? "02" : "00"));
    laser_on_ = true;
  } else if (head == "TM0" || head == "TM1" || head == "TM2") {
    if (head == "TM0") {
      const bool already = state_ == State::kTimeAdjust;
      state_ = State::kTimeAdjust;
      laser_on_ = false;
      reply(now, status_reply(line, already ? "02" : "00"));
    } else if (head == "TM2") {
      const bool was = state_ == State::kTimeAdjust;
      state_ = State::kIdle;
      reply(now, status_reply(line, was ? "00" : "03"));
    } else {
      // Real sensors answer TM1 outside time-adjust mode too.
      int64_t read = now;
      if (knobs_.tm_on_5ms_ticks || model_.tm_on_5ms_ticks) {
        const double d = device_ms(now);
        const double tick = std::ceil(d / 5.0) * 5.0;
        read = now + static_cast<int64_t>((tick - d) * 1000.0 / (1.0 + knobs_.drift_ppm * 1e-6));
      }
      const uint32_t stamp = static_cast<uint32_t>(std::floor(device_ms(read) + 1e-9)) & 0xFFFFFFu;
      const std::string value = scip_encode(stamp, 4);
      reply(read, status_reply(line, "00", value + scip_checksum(value) + "\n"));
    }
  } else if (head == "RS") {
    state_ = State::kIdle;
    laser_on_ = false;
    if (!knobs_.error_survives_reset) {
      error_latched_ = false;
      scans_total_ = 0;
    }
    reply(now, status_reply(line, "00"));
  } else if (head == "RB") {
    if (rb_count_ == 1 && now - rb_first_us_ <= 1000000) {
      reply(now, status_reply(line, "00"));
      reboot_ = true;
      rb_count_ = 0;
    } else {
      rb_count_ = 1;
      rb_first_us_ = now;
      reply(now, status_reply(line, "01"));
    }
  } else if ((head.rfind("MD", 0) == 0 || head.rfind("ME", 0) == 0) && head.size() == 15) {
    int start = 0, end = 0, cluster = 0, skip = 0, scans = 0;
    if (std::sscanf(head.c_str() + 2, "%4d%4d%2d%1d%2d", &start, &end, &cluster, &skip, &scans) != 5) {
      reply(now, status_reply(line, "01"));
      return;
    }
    if (end < start) {
      reply(now, status_reply(line, "05"));
      return;
    }
    if (start < model_.amin || end > model_.amax) {
      reply(now, status_reply(line, "04"));
      return;
    }
    if (head[1] == 'E' && !model_.intensities) {
      reply(now, status_reply(line, "0E"));
      return;
    }
    if (error_latched_) {
      reply(now, status_reply(line, knobs_.error_status.empty() ? "50" : knobs_.error_status));
      return;
    }
    intensity_ = head[1] == 'E';
    start_ = start, end_ = end, cluster_ = std::max(cluster, 1), skip_ = skip, remaining_ = scans;
    scan_echo_ = line;
    laser_on_ = true;
    state_ = State::kScanning;
    reply(now, status_reply(line, "00"));
    streaming_since_us_ = now;
    rotation_ = 0;
    fed_.clear();
    // The next rotation: first beams every period from the power-up on the host clock.
    const int64_t period = static_cast<int64_t>(60e6 / model_.scan_rpm);
    const int64_t beam_offset =
        static_cast<int64_t>(static_cast<double>(start_) / model_.ares * 60e6 / model_.scan_rpm);
    const int64_t k = (now - power_on_us_ - beam_offset) / period + 1;
    next_scan_us_ = power_on_us_ + k * period + beam_offset;
  } else {
    reply(now, status_reply(line, "0E"));
  }
}

double SimSensor::range_mm(int step) const {
  // A 6 m x 4 m room, the sensor 1.5 m from the left wall and 1 m from the bottom, a pillar of 0.3 m radius.
  const double a = (step - model_.afrt) * 2.0 * std::numbers::pi / model_.ares;
  const double c = std::cos(a), s = std::sin(a);
  double best = std::numeric_limits<double>::infinity();
  auto wall = [&](double t) {
    if (t > 0) {
      best = std::min(best, t);
    }
  };
  if (c > 1e-12)
    wall(4.5 / c);
  if (c < -1e-12)
    wall(-1.5 / c);
  if (s > 1e-12)
    wall(3.0 / s);
  if (s < -1e-12)
    wall(-1.0 / s);
  const double px = 2.0, py = 1.0, r = 0.3;
  const double b = c * px + s * py, disc = b * b - (px * px + py * py - r * r);
  if (disc >= 0 && b - std::sqrt(disc) > 0) {
    best = std::min(best, b - std::sqrt(disc));
  }
  return best * 1000.0;
}

int64_t SimSensor::scan_ready_us(int64_t first_beam_us) const {
  const int64_t period = static_cast<int64_t>(60e6 / model_.scan_rpm);
  return first_beam_us +
         static_cast<int64_t>(static_cast<double>(end_ - start_ + 1) / model_.ares * static_cast<double>(period));
}

void SimSensor::emit_scan(int64_t first_beam_us, int64_t ready, const SimScan* source) {
  const double dms = device_ms(first_beam_us);
  const uint32_t stamp = static_cast<uint32_t>(std::floor(dms)) & 0xFFFFFFu;
  std::string data;
  for (int step = start_; step <= end_; step += cluster_) {
    uint32_t value;
    const std::size_t beam = static_cast<std::size_t>(step - model_.amin);
    if (source != nullptr) {
      value = beam < source->values.size() ? source->values[beam] : 0u;
    } else if (no_echo_step(step)) {
      value = model_.name.find("URG-04") != std::string::npos ? 0u : 1u;  // a window: no echo
    } else {
      value = static_cast<uint32_t>(
          std::clamp(range_mm(step), static_cast<double>(model_.dmin), static_cast<double>(model_.dmax)));
    }
    data += scip_encode(value, 3);
    if (intensity_) {
      const bool given = source != nullptr && beam < source->intensities.size();
      data += scip_encode(given ? source->intensities[beam] : static_cast<uint32_t>(1000 + (step * 37) % 3000), 3);
    }
  }
  const std::string echo = scan_echo_.substr(0, 13) +
                           (remaining_ > 0 ? std::string(1, static_cast<char>('0' + remaining_ / 10)) +
                                                 static_cast<char>('0' + remaining_ % 10)
                                           : std::string("00")) +
                           (scan_echo_.size() > 15 ? scan_echo_.substr(15) : "");
  const std::string ts = scip_encode(stamp, 4);
  std::string bytes = echo + "\n99b\n" + ts + scip_checksum(ts) + "\n";
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const bool truncate = knobs_.truncate_rate > 0 && u(rng_) < knobs_.truncate_rate;
  const bool corrupt = knobs_.bad_checksum_rate > 0 && u(rng_) < knobs_.bad_checksum_rate;
  const std::size_t lines = (data.size() + 63) / 64;
  const std::size_t dropped = truncate ? lines / 2 : lines;
  for (std::size_t i = 0; i < lines; ++i) {
    std::string chunk = data.substr(i * 64, 64);
    const char sum = scip_checksum(chunk);
    if (corrupt && i == lines / 3) {
      chunk[5] = chunk[5] == '0' ? '1' : '0';
    }
    if (i != dropped) {
      bytes += chunk + sum + "\n";
    }
  }
  bytes += "\n";
  if (knobs_.garbage_rate > 0 && u(rng_) < knobs_.garbage_rate) {
    bytes = "#garbage\x01\xff!\n\n" + bytes;
  }
  reply(ready, bytes);
  truth_.push_back({stamp, first_beam_us, ready});
  ++scans_sent_;
}

bool SimSensor::count_scan_fails(int64_t ready) {
  ++scans_total_;
  if (knobs_.error_after < 0 || scans_total_ <= knobs_.error_after) {
    return false;
  }
  error_latched_ = true;
  state_ = State::kError;
  const std::string status = knobs_.error_status.empty() ? "50" : knobs_.error_status;
  reply(ready, status_reply(scan_echo_, status));
  return true;
}

void SimSensor::feed(SimScan scan) {
  if (state_ != State::kScanning) {
    return;  // nothing is measured for the host while it is not streaming
  }
  fed_.push_back(std::move(scan));
  while (fed_.size() > 400) {  // 10 s at 40 Hz: a source far ahead of real time
    fed_.pop_front();
  }
}

void SimSensor::poll_external(int64_t host_us) {
  const int64_t period = static_cast<int64_t>(60e6 / model_.scan_rpm);
  const int64_t to_start =
      static_cast<int64_t>(static_cast<double>(start_ - model_.amin) / model_.ares * static_cast<double>(period));
  while (state_ == State::kScanning && !fed_.empty()) {
    const SimScan& scan = fed_.front();
    const int64_t first = scan.first_beam_us + to_start;
    const int64_t ready = std::max(scan_ready_us(first), scan.received_us);
    if (ready > host_us) {
      break;
    }
    if (first >= streaming_since_us_ && rotation_++ % (1 + skip_) == 0) {
      if (count_scan_fails(ready)) {
        break;
      }
      emit_scan(first, ready, &scan);
      if (remaining_ > 0 && --remaining_ == 0) {
        state_ = State::kIdle;
      }
    }
    fed_.pop_front();
  }
}

std::string SimSensor::poll(int64_t host_us) {
  const int64_t period = static_cast<int64_t>(60e6 / model_.scan_rpm);
  if (knobs_.external_scans) {
    poll_external(host_us);
  }
  while (state_ == State::kScanning && !knobs_.external_scans) {
    const int64_t ready = scan_ready_us(next_scan_us_);
    if (ready > host_us) {
      break;
    }
    if (count_scan_fails(ready)) {
      break;
    }
    emit_scan(next_scan_us_, ready, nullptr);
    next_scan_us_ += period * (1 + skip_);
    if (remaining_ > 0 && --remaining_ == 0) {
      state_ = State::kIdle;
    }
  }
  if (state_ != State::kScanning) {
    fed_.clear();
  }
  std::string out;
  while (!out_.empty() && out_.front().due_us <= host_us) {
    out += out_.front().bytes;
    out_.pop_front();
  }
  return out;
}

int64_t SimSensor::next_event_us() const {
  int64_t next = std::numeric_limits<int64_t>::max();
  if (!out_.empty()) {
    next = out_.front().due_us;
  }
  if (state_ == State::kScanning && !knobs_.external_scans) {
    next = std::min(next, scan_ready_us(next_scan_us_));
  }
  if (state_ == State::kScanning && !fed_.empty()) {
    const int64_t period = static_cast<int64_t>(60e6 / model_.scan_rpm);
    const int64_t first = fed_.front().first_beam_us + static_cast<int64_t>(static_cast<double>(start_ - model_.amin) /
                                                                            model_.ares * static_cast<double>(period));
    next = std::min(next, std::max(scan_ready_us(first), fed_.front().received_us));
  }
  return next;
}

bool SimSensor::reboot_requested() {
  if (!reboot_) {
    return false;
  }
  reboot_ = false;
  model_ = model_after_reboot_;
  return true;
}

std::vector<SimTruth> SimSensor::take_truth() {
  std::vector<SimTruth> out;
  out.swap(truth_);
  return out;
}

}  // namespace slamer::urg

#include "drivers/urg/urg_session.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/urg/scip_codec.hpp"

namespace slamer::urg {

namespace {
std::string echo_head(const std::string& echo) {
  return echo.substr(0, echo.find(';'));
}
}  // namespace

UrgSession::UrgSession(UrgSessionOptions options) : options_(std::move(options)), clock_(options_.clock) {}

const char* UrgSession::state_name() const {
  switch (state_) {
    case State::kDisconnected:
      return "disconnected";
    case State::kProbe:
      return "probe";
    case State::kScip2:
      return "scip2_switch";
    case State::kLeaveTimeAdjust:
      return "leave_time_adjust";
    case State::kVersion:
      return "version";
    case State::kParams:
      return "parameters";
    case State::kInfo:
      return "info";
    case State::kTimeAdjustOn:
    case State::kSync:
    case State::kTimeAdjustOff:
      return "time_sync";
    case State::kLaserOn:
      return "laser_on";
    case State::kStartScan:
      return "start_scan";
    case State::kStreaming:
      return "streaming";
    case State::kReset:
      return "reset";
    case State::kReboot:
      return "reboot";
    case State::kRebooted:
      return "rebooted";
  }
  return "?";
}

void UrgSession::send(std::string_view command, int64_t now_us, std::string_view tag) {
  pending_ = std::string(command);
  pending_line_ = scip_command(command, tag);
  output_ += pending_line_;
  deadline_us_ = now_us + static_cast<int64_t>(options_.reply_timeout_s * 1e6);
  retries_left_ = options_.retries;
}

void UrgSession::connected(int64_t now_us) {
  framer_.clear();
  output_.clear();
  disconnect_ = false;
  probe_unanswered_ = false;
  probe_answered_ = false;
  clock_.reset_stream();
  unwrap_.reset();
  burst_.clear();
  tm1_send_us_.clear();
  tm1_in_flight_ = 0;
  tm1_streaming_ok_ = true;
  ++counters_.connects;
  restart(now_us);
}

void UrgSession::restart(int64_t now_us) {
  state_ = State::kProbe;
  send("QT", now_us);
}

void UrgSession::disconnected() {
  state_ = State::kDisconnected;
  pending_.clear();
  disconnect_ = false;
}

std::string UrgSession::take_output() {
  std::string out;
  out.swap(output_);
  return out;
}

std::vector<LaserScan> UrgSession::take_scans() {
  std::vector<LaserScan> out;
  out.swap(scans_);
  return out;
}

void UrgSession::received(std::string_view bytes, int64_t now_us) {
  if (state_ == State::kDisconnected) {
    return;
  }
  framer_.feed(bytes);
  const int64_t overflows_before = framer_.overflows();
  std::vector<std::string> lines;
  while (framer_.next(&lines)) {
    const Reply reply = parse_reply(lines);
    if (!reply.empty) {
      handle(reply, now_us);
    }
  }
  counters_.overflows += framer_.overflows() - overflows_before;
}

void UrgSession::fail(const std::string& why, bool malfunction, int64_t now_us) {
  error(why);
  ++(malfunction ? counters_.malfunctions : counters_.command_errors);
  ++consecutive_failures_;
  if (consecutive_failures_ > options_.resets_before_reboot) {
    consecutive_failures_ = 0;
    ++counters_.reboots;
    state_ = State::kReboot;
    first_rb_us_ = now_us;
    send("RB", now_us);
  } else {
    ++counters_.resets;
    state_ = State::kReset;
    send("RS", now_us);
  }
}

void UrgSession::start_stream(int64_t now_us) {
  start_step_ = options_.first_step >= 0 ? std::max(options_.first_step, geometry_.amin) : geometry_.amin;
  end_step_ = options_.last_step >= 0 ? std::min(options_.last_step, geometry_.amax) : geometry_.amax;
  if (end_step_ < start_step_) {
    end_step_ = start_step_;
  }
  state_ = State::kStartScan;
  const std::string line =
      scip_scan_command(options_.intensities, start_step_, end_step_, std::clamp(options_.cluster, 1, 99), 0, 0);
  send(line.substr(0, line.size() - 1), now_us);
}

void UrgSession::handle(const Reply& reply, int64_t now_us) {
  const std::string head = echo_head(reply.echo);
  // Scan data (and the start acknowledgement of MD/ME) are matched by their echo.
  if ((reply.command == "MD" || reply.command == "ME") && reply.kind() != StatusKind::kOk) {
    if (state_ == State::kStartScan || state_ == State::kStreaming) {
      handle_scan(reply, now_us);
    } else if (state_ != State::kProbe) {
      ++counters_.stray;  // a stream we stopped (drained)
    }
    return;
  }
  // TM1 sent between scans.
  if (reply.command == "TM" && !reply.tag.empty() && reply.tag[0] == 'p') {
    --tm1_in_flight_;
    const std::size_t id = static_cast<std::size_t>(std::strtoll(reply.tag.c_str() + 1, nullptr, 10));
    if (reply.status != "00" || !reply.checksum_ok() || reply.lines.empty() || reply.lines[0].size() != 5 ||
        !line_checksum_ok(reply.lines[0])) {
      tm1_streaming_ok_ = reply.status == "00";  // refused outside time-adjust mode: stop asking
      return;
    }
    const auto value = scip_decode(std::string_view(reply.lines[0]).substr(0, 4));
    if (value && id < tm1_send_us_.size() && tm1_send_us_[id] > 0) {
      clock_.add_sync_sample({tm1_send_us_[id], now_us, unwrap_.unwrap(static_cast<uint32_t>(*value))});
      tm1_send_us_[id] = 0;
    }
    return;
  }
  if (pending_.empty() || head != pending_) {
    if (state_ != State::kProbe) {
      ++counters_.stray;
    }
    return;
  }
  pending_.clear();
  const StatusKind kind = reply.kind();
  if (!reply.checksum_ok() && !reply.scip1) {
    // A damaged reply: ask again.
    ++counters_.checksum;
    send(head, now_us, reply.tag);
    return;
  }
  switch (state_) {
    case State::kProbe:
      probe_answered_ = true;
      if (reply.scip1) {
        state_ = State::kScip2;
        ++counters_.scip1_switches;
        send("SCIP2.0", now_us);
      } else if (kind == StatusKind::kTimeAdjust) {
        state_ = State::kLeaveTimeAdjust;
        send("TM2", now_us);
      } else if (kind == StatusKind::kOk || kind == StatusKind::kBenign) {
        state_ = State::kVersion;
        send("VV", now_us);
      } else {
        fail("QT refused with status " + reply.status, kind == StatusKind::kMalfunction, now_us);
      }
      return;
    case State::kScip2:
    case State::kLeaveTimeAdjust:
      restart(now_us);  // probe again: now SCIP 2.0 / out of time-adjust mode
      return;
    case State::kVersion: {
      const KeyValues kv = parse_key_values(reply);
      if (const auto* serial = kv.find("SERI")) {
        serial_ = *serial;
      }
      if (const auto* product = kv.find("PROD")) {
        model_ = *product;
      }
      state_ = State::kParams;
      send("PP", now_us);
      return;
    }
    case State::kParams: {
      std::string why;
      SensorGeometry geometry;
      if (kind != StatusKind::kOk || !parse_geometry(parse_key_values(reply), &geometry, &why)) {
        fail(kind != StatusKind::kOk ? "PP refused with status " + reply.status : why, kind == StatusKind::kMalfunction,
             now_us);
        return;
      }
      geometry_ = geometry;
      if (!geometry_.model.empty()) {
        model_ = geometry_.model;
      }
      state_ = State::kInfo;
      send("II", now_us);
      return;
    }
    case State::kInfo: {
      const KeyValues kv = parse_key_values(reply);
      if (const auto* serial = kv.find("SERI"); serial != nullptr && serial_.empty()) {
        serial_ = *serial;
      }
      if (kind == StatusKind::kMalfunction) {
        fail("II reports a sensor error", true, now_us);
        return;
      }
      if (options_.sync_samples > 0) {
        state_ = State::kTimeAdjustOn;
        send("TM0", now_us);
      } else {
        state_ = State::kLaserOn;
        send("BM", now_us);
      }
      return;
    }
    case State::kTimeAdjustOn:
      if (kind == StatusKind::kOk || kind == StatusKind::kBenign) {
        state_ = State::kSync;
        burst_.clear();
        tm1_send_us_.assign(1, now_us);
        send("TM1", now_us);
      } else {
        error("TM0 refused with status " + reply.status + "; running without time sync");
        state_ = State::kLaserOn;
        send("BM", now_us);
      }
      return;
    case State::kSync:
      if (kind == StatusKind::kOk && !reply.lines.empty() && reply.lines[0].size() == 5) {
        const auto value = scip_decode(std::string_view(reply.lines[0]).substr(0, 4));
        if (value) {
          burst_.push_back({tm1_send_us_[0], now_us, unwrap_.unwrap(static_cast<uint32_t>(*value))});
        }
      }
      if (kind == StatusKind::kOk && static_cast<int>(burst_.size()) < options_.sync_samples) {
        tm1_send_us_[0] = now_us;
        send("TM1", now_us);
        return;
      }
      clock_.sync(burst_);
      state_ = State::kTimeAdjustOff;
      send("TM2", now_us);
      return;
    case State::kTimeAdjustOff:
      state_ = State::kLaserOn;
      send("BM", now_us);
      return;
    case State::kLaserOn:
      if (kind == StatusKind::kOk || kind == StatusKind::kBenign) {
        start_stream(now_us);
      } else {
        fail("BM refused with status " + reply.status, kind == StatusKind::kMalfunction, now_us);
      }
      return;
    case State::kStartScan:
      if (kind == StatusKind::kOk) {
        state_ = State::kStreaming;
        last_data_us_ = now_us;
        next_tm1_us_ = now_us;
      } else {
        fail(reply.command + " refused with status " + reply.status, kind == StatusKind::kMalfunction, now_us);
      }
      return;
    case State::kReset:
      restart(now_us);
      return;
    case State::kReboot:
      if (reply.status == "01") {
        send("RB", now_us);  // the second RB within 1 s
      } else {
        state_ = State::kRebooted;
        disconnect_ = true;  // the sensor restarts: reconnect
      }
      return;
    default:
      ++counters_.stray;
      return;
  }
}

void UrgSession::handle_scan(const Reply& reply, int64_t now_us) {
  const StatusKind kind = reply.kind();
  if (kind == StatusKind::kMalfunction) {
    fail("scan status " + reply.status + " (laser malfunction)", true, now_us);
    return;
  }
  if (kind != StatusKind::kScanData) {
    if (kind == StatusKind::kBenign) {
      return;  // 98: resumed after a check
    }
    fail(reply.command + " status " + reply.status, false, now_us);
    return;
  }
  if (state_ == State::kStartScan) {
    state_ = State::kStreaming;  // the 00 acknowledgement was lost: data proves the stream runs
    pending_.clear();
    next_tm1_us_ = now_us;
  }
  last_data_us_ = now_us;
  ScanData data;
  const ScanError result = decode_scan(reply, &data);
  switch (result) {
    case ScanError::kOk:
      break;
    case ScanError::kChecksum:
      ++counters_.checksum;
      return;
    case ScanError::kTruncated:
      ++counters_.truncated;
      return;
    case ScanError::kBadChar:
      ++counters_.bad_char;
      return;
    default:
      ++counters_.length;
      return;
  }
  if (data.params.start != start_step_ || data.params.end != end_step_ ||
      data.params.intensity != options_.intensities) {
    ++counters_.stray;  // a stream requested before this session
    return;
  }
  const int64_t device_ms = unwrap_.unwrap(data.timestamp_ms);
  const int64_t period_us = std::llround(geometry_.scan_period() * 1e6);
  LaserScan scan;
  scan.utime = clock_.scan_utime(device_ms, period_us, now_us);
  scan.sensor_utime = device_ms * 1000;
  scan.seq = scan_seq_++;
  scan.frame = options_.frame;
  const int cluster = std::max(data.params.cluster, 1);
  scan.angle_min = geometry_.angle_of_step(start_step_);
  scan.angle_increment = geometry_.angle_increment() * cluster;
  scan.range_min = static_cast<float>(geometry_.dmin / 1000.0);
  scan.range_max = static_cast<float>(geometry_.dmax / 1000.0);
  scan.time_increment = static_cast<float>(geometry_.time_increment() * cluster);
  scan.scan_period = static_cast<float>(geometry_.scan_period());
  scan.ranges.reserve(data.distances.size());
  for (const uint32_t value : data.distances) {
    scan.ranges.push_back(range_from_device(value, geometry_));
  }
  scan.intensities.assign(data.intensities.begin(), data.intensities.end());
  scans_.push_back(std::move(scan));
  ++counters_.scans;
  if (counters_.scans % 40 == 0) {
    consecutive_failures_ = 0;
  }
}

void UrgSession::tick(int64_t now_us) {
  if (state_ == State::kDisconnected || disconnect_) {
    return;
  }
  if (state_ == State::kStreaming) {
    const double period_us = geometry_.scan_period() * 1e6;
    const int64_t silence_us = std::max<int64_t>(std::llround(options_.silence_periods * period_us), 100000);
    if (now_us - last_data_us_ > silence_us) {
      ++counters_.silences;
      error("no data for " + std::to_string((now_us - last_data_us_) / 1000) + " ms");
      disconnect_ = true;
      return;
    }
    if (tm1_in_flight_ >= 4 && now_us > next_tm1_us_ + 1'000'000) {
      tm1_in_flight_ = 0;  // replies lost (damaged, drained): ask again
    }
    if (options_.tm1_while_streaming_hz > 0 && tm1_streaming_ok_ && now_us >= next_tm1_us_ && tm1_in_flight_ < 4) {
      const auto id = static_cast<std::size_t>(tm1_seq_++ % 64);
      tm1_send_us_.resize(64, 0);
      tm1_send_us_[id] = now_us;
      output_ += scip_command("TM1", "p" + std::to_string(id));
      ++tm1_in_flight_;
      next_tm1_us_ = now_us + static_cast<int64_t>(1e6 / options_.tm1_while_streaming_hz);
    }
    return;
  }
  if (!pending_.empty() && now_us > deadline_us_) {
    ++counters_.timeouts;
    if (state_ == State::kReboot && pending_ == "RB" && now_us - first_rb_us_ > 500000) {
      disconnect_ = true;  // the sensor went away to reboot
      return;
    }
    if (retries_left_ > 0) {
      --retries_left_;
      output_ += pending_line_;
      deadline_us_ = now_us + static_cast<int64_t>(options_.reply_timeout_s * 1e6);
      return;
    }
    error("no reply to " + pending_);
    if (state_ == State::kProbe && !probe_answered_) {
      probe_unanswered_ = true;
    }
    disconnect_ = true;
  }
}

}  // namespace slamer::urg

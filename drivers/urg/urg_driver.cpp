#include "drivers/urg/urg_driver.hpp"

#include <poll.h>

#include <algorithm>
#include <ctime>

namespace slamer::urg {

int64_t host_now_us() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

UrgDriver::UrgDriver(const UrgProcessConfig& config) : config_(config), session_(config.session) {
  if (!config_.connection.device.empty()) {
    transport_ = std::make_unique<SerialTransport>(config_.connection.device);
  } else {
    transport_ = std::make_unique<TcpTransport>(config_.connection.host, config_.connection.port,
                                                config_.connection.connect_timeout_s);
  }
}

void UrgDriver::try_connect(int64_t now) {
  std::string error;
  if (!transport_->open(&error)) {
    last_error_ = error;
    next_attempt_us_ = host_now_us() + static_cast<int64_t>(backoff_s_ * 1e6);
    backoff_s_ = std::min(backoff_s_ * 2, config_.connection.max_backoff_s);
    return;
  }
  if (ever_connected_) {
    ++reconnects_;
  }
  ever_connected_ = true;
  (void)now;
  session_.connected(host_now_us());
  flush(host_now_us());
}

void UrgDriver::drop(const std::string& why, int64_t now) {
  last_error_ = why;
  if (session_.probe_unanswered()) {
    transport_->next_baud();  // a serial sensor at another rate
  }
  transport_->close();
  session_.disconnected();
  next_attempt_us_ = now + static_cast<int64_t>(backoff_s_ * 1e6);
  backoff_s_ = std::min(backoff_s_ * 2, config_.connection.max_backoff_s);
}

void UrgDriver::flush(int64_t now) {
  const std::string out = session_.take_output();
  std::string error;
  if (!out.empty() && !transport_->write(out, &error)) {
    drop(error, now);
  }
}

void UrgDriver::step(int timeout_ms) {
  int64_t now = host_now_us();
  if (!transport_->is_open()) {
    if (now >= next_attempt_us_) {
      try_connect(now);
    } else {
      pollfd none{};
      poll(&none, 0, std::min<int>(timeout_ms, static_cast<int>((next_attempt_us_ - now) / 1000) + 1));
    }
    return;
  }
  pollfd p{transport_->fd(), POLLIN, 0};
  const int ready = poll(&p, 1, timeout_ms);
  now = host_now_us();  // the arrival time of what was read
  if (ready > 0) {
    std::string bytes, error;
    const bool ok = transport_->read(&bytes, &error);
    if (!bytes.empty()) {
      session_.received(bytes, now);
    }
    if (!ok) {
      drop(error, now);
      return;
    }
  }
  session_.tick(now);
  if (session_.streaming()) {
    backoff_s_ = 0.1;
  }
  flush(now);
  if (transport_->is_open() && session_.should_disconnect()) {
    drop(session_.last_error().empty() ? "the sensor stopped answering" : session_.last_error(), now);
  }
}

UrgDriverStatus UrgDriver::status() const {
  UrgDriverStatus s;
  s.connected = transport_->is_open();
  s.streaming = session_.streaming();
  s.where = transport_->describe();
  s.state = session_.state_name();
  s.model = session_.model();
  s.serial = session_.serial();
  s.last_error = last_error_.empty() ? session_.last_error() : last_error_;
  s.counters = session_.counters();
  s.reconnects = reconnects_;
  s.synced = session_.clock().synced();
  s.sync_width_us = session_.clock().sync_width_us();
  s.drift_ppm = session_.clock().drift_ppm();
  return s;
}

}  // namespace slamer::urg

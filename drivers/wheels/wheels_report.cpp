#include "drivers/wheels/wheels_report.hpp"

#include <cmath>
#include <cstdio>

namespace slamer {

namespace {
constexpr int8_t kOk = 0;
constexpr int8_t kDegraded = 1;

std::string fixed(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", value);
  return text;
}
}  // namespace

std::optional<tfrog::OdometrySample> CanOdometry::feed(const can::CanFrame& frame) {
  const auto sample = decoder_.feed(frame);
  if (!sample) {
    return std::nullopt;
  }
  const double dt = last_utime_ > 0 ? static_cast<double>(sample->utime - last_utime_) * 1e-6 : 0.0;
  last_utime_ = sample->utime;
  integrator_.add(sample->delta, dt);
  return tfrog::OdometrySample{sample->utime, integrator_.pose(), integrator_.v(), integrator_.omega(), sample->ticks};
}

std::array<int64_t, 2> forward_ticks(const std::array<int64_t, 2>& motor_ticks, const tfrog::Kinematics& kinematics) {
  auto sign = [](double r) { return r < 0.0 ? int64_t{-1} : int64_t{1}; };
  return {motor_ticks[1] * sign(kinematics.radius[1]), motor_ticks[0] * sign(kinematics.radius[0])};
}

Report tfrog_report(const tfrog::SessionStatus& s, double frame_rate, const std::string& device) {
  Report report;
  const auto& id = s.identity;
  std::string board = id.protocol.empty() ? "board not identified"
                                          : id.vendor + " / " + id.product + " serial " + id.serial + " " + id.protocol;
  if (s.protocol_warning) {
    board += " (older protocol than YPP:11)";
  }
  std::string errors;
  for (int m = 0; m < 2; ++m) {
    if (s.error_bits[static_cast<std::size_t>(m)] != 0) {
      errors += " motor" + std::to_string(m) + "=" + tfrog::error_bits_text(s.error_bits[static_cast<std::size_t>(m)]);
    }
  }
  report.message = std::string("tfrog ") + device + " " + tfrog::to_string(s.link) + "; " + board + "; " +
                   fixed(frame_rate) + " Hz; frames " + std::to_string(s.frames) + ", lost " +
                   std::to_string(s.lost_frames) + ", damaged " + std::to_string(s.bad_frames) + ", wrong length " +
                   std::to_string(s.wrong_length) + "; reconnects " + std::to_string(s.reconnects) + "; command " +
                   tfrog::to_string(s.drive) + (errors.empty() ? "" : "; errors" + errors);
  if (s.link != tfrog::LinkState::kRunning) {
    report.state = kDegraded;
    report.message += "; " + s.last_problem;
  } else if (!errors.empty()) {
    report.state = kDegraded;
  } else {
    report.state = kOk;
  }
  return report;
}

Report can_report(const can::BusStatus& bus, double frame_rate, bool connected, bool silent,
                  const std::string& interface) {
  Report report;
  report.message = "can " + interface + (connected ? "" : " not connected") + "; " + fixed(frame_rate) +
                   " Hz; frames " + std::to_string(bus.frames) + ", error frames " + std::to_string(bus.error_frames) +
                   ", lost arbitration " + std::to_string(bus.lost_arbitration) + ", short " +
                   std::to_string(bus.short_frames) + (bus.bus_off ? "; BUS-OFF" : "") +
                   (bus.error_passive ? "; error-passive" : "") + (silent ? "; no encoder frames" : "");
  report.state = (!connected || bus.bus_off || bus.error_passive || silent) ? kDegraded : kOk;
  return report;
}

}  // namespace slamer

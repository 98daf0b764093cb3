// What slamer-wheels reports: the CAN backend's odometry (decoder + exact-arc
// integration + silence), the one-line PROCESS_STATUS message and state of
// either backend, and the wheel_encoders_t sign convention. Pure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "drivers/wheels/can_decoder.hpp"
#include "drivers/wheels/tfrog_session.hpp"

namespace slamer {

// Odometry from CAN frames through the robot's kinematics.
class CanOdometry {
 public:
  CanOdometry(const can::CanLayout& layout, const tfrog::Kinematics& kinematics)
      : decoder_(layout), integrator_(kinematics) {}
  std::optional<tfrog::OdometrySample> feed(const can::CanFrame& frame);
  const can::BusStatus& bus() const { return decoder_.status(); }
  std::vector<uint32_t> ids() const { return decoder_.ids(); }
  int64_t last_frame_utime() const { return last_utime_; }

 private:
  can::CanDecoder decoder_;
  tfrog::DiffDriveIntegrator integrator_;
  int64_t last_utime_ = 0;
};

// Wheel ticks for wheel_encoders_t: [0] left = motor 1, [1] right = motor 0,
// each multiplied by the sign of its radius so forward is positive.
std::array<int64_t, 2> forward_ticks(const std::array<int64_t, 2>& motor_ticks, const tfrog::Kinematics& kinematics);

struct Report {
  int8_t state = 0;  // process_status_t OK / DEGRADED / ERROR
  std::string message;
};
// frame_rate: frames per second over the last status period.
Report tfrog_report(const tfrog::SessionStatus& status, double frame_rate, const std::string& device);
Report can_report(const can::BusStatus& bus, double frame_rate, bool connected, bool silent,
                  const std::string& interface);

}  // namespace slamer

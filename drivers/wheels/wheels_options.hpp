// Options of slamer-wheels (config/wheels.yaml), defaults in one place, read by
// the strict loader. `robot_param` names a YP-Spur .param file (relative to
// the config file); `robot_params` gives the same keys inline instead.
#pragma once

#include <string>

#include "common/config/config_reader.hpp"
#include "common/process/process_options.hpp"
#include "drivers/wheels/can_decoder.hpp"
#include "drivers/wheels/tfrog_session.hpp"
#include "drivers/wheels/ypspur_params.hpp"

namespace slamer {

struct WheelsTfrogOptions {
  std::string device = "/dev/ttyACM0";  // reopened by this path (a udev symlink) after an unplug
  double reopen_period = 0.2;           // [s]
  tfrog::SessionOptions session;
};

struct WheelsCanOptions {
  std::string interface = "can0";  // or "unix:PATH": a SOCK_SEQPACKET socket carrying can_frames
  can::CanLayout layout;
};

struct WheelsChannels {
  std::string odometry = "ODOMETRY";
  std::string wheel_encoders = "WHEEL_ENCODERS";
  std::string cmd_vel = "CMD_VEL";
};

struct WheelsConfig {
  std::string backend = "tfrog";  // tfrog | can
  std::string robot_param = "robots/icart-mini.param";
  tfrog::RobotParams robot;    // loaded from robot_param or robot_params
  double poll_period = 0.002;  // [s] device polling / session tick
  WheelsTfrogOptions tfrog;
  WheelsCanOptions can;
  WheelsChannels channels;
  ProcessOptions process;
};

void read_options(const ConfigReader& reader, WheelsConfig* config);

}  // namespace slamer

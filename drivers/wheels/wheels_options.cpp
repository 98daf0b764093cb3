#include "drivers/wheels/wheels_options.hpp"

namespace slamer {

namespace {

void read_session(const ConfigReader& reader, tfrog::SessionOptions* options) {
  std::string level = options->free_level == tfrog::ServoLevel::kTorque     ? "torque"
                      : options->free_level == tfrog::ServoLevel::kOpenFree ? "open_free"
                                                                            : "counter";
  reader.read_choice("free_level", &level, {"counter", "torque", "open_free"});
  options->free_level = level == "torque"      ? tfrog::ServoLevel::kTorque
                        : level == "open_free" ? tfrog::ServoLevel::kOpenFree
                                               : tfrog::ServoLevel::kCounter;
  reader.read("high_resolution", &options->high_resolution);
  reader.read("watchdog_ms", &options->watchdog_ms, in_range(20, 10000));
  reader.read("control_cycle", &options->control_cycle, in_range(0.001, 0.1));
  reader.read("silence_timeout", &options->silence_timeout, in_range(0.05, 10.0));
  reader.read("reply_timeout", &options->reply_timeout, in_range(0.05, 10.0));
  reader.read("use_embedded_param", &options->use_embedded_param);
}

}  // namespace

void read_options(const ConfigReader& reader, WheelsConfig* config) {
  reader.read_choice("backend", &config->backend, {"tfrog", "can"});
  reader.read("poll_period", &config->poll_period, in_range(0.0005, 0.02));
  if (reader.has("robot_params")) {
    if (reader.has("robot_param")) {
      reader.fail("robot_params", "give robot_param (a .param file) or robot_params, not both");
    }
    config->robot = tfrog::RobotParams::from_yaml(reader.section("robot_params"));
    config->robot_param.clear();
  } else {
    reader.read("robot_param", &config->robot_param);
    config->robot_param = reader.resolve_path(config->robot_param);
    try {
      config->robot = tfrog::RobotParams::from_file(config->robot_param);
    } catch (const ConfigError& e) {
      reader.fail("robot_param", e.what());
    }
  }
  try {
    (void)tfrog::kinematics_from(config->robot);
  } catch (const ConfigError& e) {
    reader.fail(reader.has("robot_params") ? "robot_params" : "robot_param", e.what());
  }
  const ConfigReader tfrog = reader.section("tfrog");
  tfrog.read("device", &config->tfrog.device);
  tfrog.read("reopen_period", &config->tfrog.reopen_period, in_range(0.01, 10.0));
  read_session(tfrog, &config->tfrog.session);
  const ConfigReader command = reader.section("command");
  command.read("timeout", &config->tfrog.session.cmd_timeout, in_range(0.01, 0.3));
  std::string stop = config->tfrog.session.timeout_servo_stop ? "servo_stop" : "zero_velocity";
  command.read_choice("stop", &stop, {"zero_velocity", "servo_stop"});
  config->tfrog.session.timeout_servo_stop = stop == "servo_stop";
  const ConfigReader can = reader.section("can");
  can.read("interface", &config->can.interface);
  read_options(can, &config->can.layout);
  const ConfigReader channels = reader.section("channels");
  channels.read("odometry", &config->channels.odometry);
  channels.read("wheel_encoders", &config->channels.wheel_encoders);
  channels.read("cmd_vel", &config->channels.cmd_vel);
  read_options(reader.section("process"), &config->process);
}

}  // namespace slamer

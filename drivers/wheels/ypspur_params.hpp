// YP-Spur robot parameters: the `.param` file format ("KEY value" for both
// motors, "KEY[i] value" for motor i, '#' comments) or the same keys in YAML,
// and the board parameters ypspur-coordinator computes from them at connect
// (tfrog.md section 3: set_param_motor / set_param_velocity, inertia of
// calc_param_inertia2ff). Values are truncated to int32 as YP-Spur's integer
// parameter does. Pure: no I/O.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "drivers/wheels/tfrog_codec.hpp"
#include "drivers/wheels/tfrog_text.hpp"

namespace slamer::tfrog {

// Per-motor values by key; a key given without an index fills both motors.
class RobotParams {
 public:
  // Throws ConfigError "SOURCE:LINE: problem" for a malformed line.
  static RobotParams parse(const std::string& text, const std::string& source);
  static RobotParams from_file(const std::string& path);
  // YAML mapping of the same keys: `COUNT_REV: 400`, `"RADIUS[0]": 0.07455`.
  static RobotParams from_yaml(const ConfigReader& reader);

  void set(const std::string& key, int motor, double value);  // motor -1: both
  bool has(const std::string& key, int motor) const;
  // The value, or `fallback` when unset.
  double get(const std::string& key, int motor, double fallback) const;
  // The value; throws ConfigError naming the key when unset.
  double require(const std::string& key, int motor) const;
  const std::string& source() const { return source_; }

 private:
  std::map<std::string, std::array<std::optional<double>, 2>> values_;
  std::string source_;
};

// The robot parameters the driver uses, per motor 0 (right) and 1 (left).
struct Kinematics {
  std::array<double, 2> radius{};                // signed [m]
  double tread = 0.0;                            // [m]
  std::array<double, 2> counts_per_wheel_rev{};  // COUNT_REV * |GEAR|
  double cycle = 0.001;                          // board control cycle [s]
  double max_vel = 0.0;
  double max_w = 0.0;
  double max_acc_v = 0.0;
  double max_acc_w = 0.0;
};
Kinematics kinematics_from(const RobotParams& params);

// The parameter commands sent at connect, in YP-Spur's order: watchdog 1200,
// w_ref 0, protocol version (device >= 10), motor parameters (per motor),
// velocity-control parameters, watchdog `watchdog_ms`. Each group is one
// element so the caller can pause between groups.
std::vector<std::vector<Command>> connect_parameters(const RobotParams& params, int pwm_max, int device_version,
                                                     int watchdog_ms);

}  // namespace slamer::tfrog

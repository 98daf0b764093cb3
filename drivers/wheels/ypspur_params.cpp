#include "drivers/wheels/ypspur_params.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace slamer::tfrog {

namespace {

// YP-Spur converts each double to its integer parameter by truncation.
int32_t to_value(double value) {
  if (!std::isfinite(value)) {
    return 0;
  }
  const double t = std::trunc(value);
  if (t > 2147483647.0) {
    return std::numeric_limits<int32_t>::max();
  }
  if (t < -2147483646.0) {
    return -2147483646;
  }
  return static_cast<int32_t>(t);
}

Command cmd(Param param, int motor, double value) {
  return Command{static_cast<uint8_t>(param), static_cast<uint8_t>(motor), to_value(value)};
}

// "KEY" or "KEY[i]" -> (KEY, i or -1); false when malformed.
bool split_key(const std::string& token, std::string* key, int* motor) {
  const auto open = token.find('[');
  if (open == std::string::npos) {
    *key = token;
    *motor = -1;
    return !token.empty();
  }
  if (open == 0 || token.size() != open + 3 || token[open + 2] != ']' ||
      (token[open + 1] != '0' && token[open + 1] != '1')) {
    return false;
  }
  *key = token.substr(0, open);
  *motor = token[open + 1] - '0';
  return true;
}

}  // namespace

void RobotParams::set(const std::string& key, int motor, double value) {
  auto& slot = values_[key];
  if (motor < 0) {
    slot[0] = value;
    slot[1] = value;
  } else {
    slot[static_cast<std::size_t>(motor)] = value;
  }
}

bool RobotParams::has(const std::string& key, int motor) const {
  const auto it = values_.find(key);
  return it != values_.end() && it->second[static_cast<std::size_t>(motor)].has_value();
}

double RobotParams::get(const std::string& key, int motor, double fallback) const {
  const auto it = values_.find(key);
  if (it == values_.end() || !it->second[static_cast<std::size_t>(motor)]) {
    return fallback;
  }
  return *it->second[static_cast<std::size_t>(motor)];
}

double RobotParams::require(const std::string& key, int motor) const {
  if (!has(key, motor)) {
    throw ConfigError(source_ + ": robot parameter " + key + "[" + std::to_string(motor) + "] is not set");
  }
  return get(key, motor, 0.0);
}

RobotParams RobotParams::parse(const std::string& text, const std::string& source) {
  RobotParams params;
  params.source_ = source;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) {
      line.resize(hash);
    }
    std::istringstream fields(line);
    std::string token;
    if (!(fields >> token)) {
      continue;
    }
    std::string value_text;
    if (!(fields >> value_text)) {
      throw ConfigError(source + ":" + std::to_string(number) + ": '" + token + "' has no value");
    }
    std::string key;
    int motor = -1;
    if (!split_key(token, &key, &motor)) {
      throw ConfigError(source + ":" + std::to_string(number) + ": malformed parameter name '" + token + "'");
    }
    char* end = nullptr;
    const double value = std::strtod(value_text.c_str(), &end);
    if (end == value_text.c_str() || *end != '\0' || !std::isfinite(value)) {
      throw ConfigError(source + ":" + std::to_string(number) + ": " + token + ": '" + value_text +
                        "' is not a finite number");
    }
    params.set(key, motor, value);
  }
  return params;
}

RobotParams RobotParams::from_file(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw ConfigError(path + ": cannot open the robot parameter file");
  }
  std::stringstream text;
  text << file.rdbuf();
  return parse(text.str(), path);
}

RobotParams RobotParams::from_yaml(const ConfigReader& reader) {
  RobotParams params;
  params.source_ = reader.source();
  for (const std::string& token : reader.keys()) {
    std::string key;
    int motor = -1;
    if (!split_key(token, &key, &motor)) {
      reader.fail(token, "malformed parameter name (KEY or KEY[0]/KEY[1])");
    }
    double value = 0.0;
    reader.read(token, &value);
    params.set(key, motor, value);
  }
  return params;
}

Kinematics kinematics_from(const RobotParams& params) {
  Kinematics k;
  for (int m = 0; m < 2; ++m) {
    const auto i = static_cast<std::size_t>(m);
    k.radius[i] = params.require("RADIUS", m);
    k.counts_per_wheel_rev[i] = params.require("COUNT_REV", m) * std::fabs(params.require("GEAR", m));
    if (!(k.counts_per_wheel_rev[i] > 0.0) || k.radius[i] == 0.0) {
      throw ConfigError(params.source() + ": COUNT_REV, GEAR and RADIUS must be non-zero");
    }
  }
  k.tread = params.require("TREAD", 0);
  k.cycle = params.get("CYCLE", 0, 0.001);
  k.max_vel = params.require("MAX_VEL", 0);
  k.max_w = params.require("MAX_W", 0);
  k.max_acc_v = params.require("MAX_ACC_V", 0);
  k.max_acc_w = params.require("MAX_ACC_W", 0);
  if (!(k.tread > 0.0) || !(k.cycle > 0.0) || !(k.max_vel > 0.0) || !(k.max_w > 0.0) || !(k.max_acc_v > 0.0) ||
      !(k.max_acc_w > 0.0)) {
    throw ConfigError(params.source() + ": TREAD, CYCLE, MAX_VEL, MAX_W, MAX_ACC_V and MAX_ACC_W must be > 0");
  }
  return k;
}

std::vector<std::vector<Command>> connect_parameters(const RobotParams& p, int pwm_max, int device_version,
                                                     int watchdog_ms) {
  std::vector<std::vector<Command>> groups;
  groups.push_back({cmd(Param::kWatchDogLimit, 0, 1200), cmd(Param::kWatchDogLimit, 1, 1200)});
  groups.push_back({cmd(Param::kWRef, 0, 0), cmd(Param::kWRef, 1, 0)});
  if (device_version >= 10) {
    groups.push_back(
        {cmd(Param::kProtocolVersion, 0, kHostProtocolCurrent), cmd(Param::kProtocolVersion, 1, kHostProtocolCurrent)});
  }
  // Inertia as calc_param_inertia2ff computes it for a two-wheel vehicle.
  const double mass = p.get("MASS", 0, 0.0);
  const double moment = p.get("MOMENT_INERTIA", 0, 0.0);
  const double tread = p.require("TREAD", 0);
  const double rr = p.require("RADIUS", 0);
  const double rl = p.require("RADIUS", 1);
  const double gr = std::fabs(p.require("GEAR", 0));
  const double gl = std::fabs(p.require("GEAR", 1));
  const double jt = moment / (tread * tread);
  const std::array<double, 2> inertia_self = {(gr * gr * p.get("MOTOR_M_INERTIA", 0, 0.0) +
                                               p.get("TIRE_M_INERTIA", 0, 0.0) + rr * rr / 2.0 * (mass / 2.0 + jt)) /
                                                  gr,
                                              (gl * gl * p.get("MOTOR_M_INERTIA", 1, 0.0) +
                                               p.get("TIRE_M_INERTIA", 1, 0.0) + rl * rl / 2.0 * (mass / 2.0 + jt)) /
                                                  gl};
  const std::array<double, 2> inertia_cross = {(rr * rl / 2.0 * (mass / 2.0 - jt)) / gr,
                                               (rr * rl / 2.0 * (mass / 2.0 - jt)) / gl};

  for (int j = 0; j < 2; ++j) {
    const double volt = p.require("VOLT", j);
    const double cycle = p.get("CYCLE", j, 0.001);
    const double count_rev = p.require("COUNT_REV", j);
    const double denominator = p.get("ENCODER_DENOMINATOR", j, 1.0);
    const double torque_unit = 1.0 / p.get("TORQUE_FINENESS", j, 1e-6);
    const double pwm = pwm_max;
    std::vector<Command> motor;
    motor.push_back(cmd(Param::kVsrc, j, volt * 256.0));
    motor.push_back(cmd(Param::kControlCycle, j, cycle * 1000.0));
    motor.push_back(cmd(Param::kMotorPhase, j, p.get("MOTOR_PHASE", j, 3.0)));
    motor.push_back(
        cmd(Param::kPhaseOffset, j, p.get("PHASE_OFFSET", j, 0.0) * (count_rev / denominator) / (2.0 * M_PI)));
    if (p.has("ENCODER_TYPE", j)) {
      motor.push_back(cmd(Param::kEncType, j, p.get("ENCODER_TYPE", j, 0.0)));
    }
    if (p.has("ENCODER_DIV", j)) {
      motor.push_back(cmd(Param::kEncDiv, j, p.get("ENCODER_DIV", j, 0.0)));
    }
    motor.push_back(
        cmd(Param::kPKi, j,
            65536.0 * pwm * p.require("MOTOR_R", j) * denominator / (torque_unit * p.require("MOTOR_TC", j) * volt)));
    motor.push_back(cmd(Param::kPKv, j, 65536.0 * pwm * 60.0 / (p.require("MOTOR_VC", j) * volt * count_rev * cycle)));
    const double newton = p.get("TORQUE_NEWTON", j, 0.0);
    motor.push_back(cmd(Param::kFrPlus, j, newton * torque_unit));
    motor.push_back(cmd(Param::kFrMinus, j, p.get("TORQUE_NEWTON_NEG", j, newton) * torque_unit));
    const double tvc = (2.0 * M_PI / count_rev) / cycle;
    const double viscos = p.get("TORQUE_VISCOS", j, 0.0);
    motor.push_back(cmd(Param::kFrWPlus, j, viscos * torque_unit * tvc));
    motor.push_back(cmd(Param::kFrWMinus, j, p.get("TORQUE_VISCOS_NEG", j, viscos) * torque_unit * tvc));
    motor.push_back(cmd(Param::kToqOffset, j, p.get("TORQUE_OFFSET", j, 0.0) * torque_unit));
    const double torque_max = p.require("TORQUE_MAX", j);
    motor.push_back(cmd(Param::kToqMax, j, torque_max * torque_unit));
    motor.push_back(cmd(Param::kToqMin, j, -torque_max * torque_unit));
    motor.push_back(cmd(Param::kToqLimit, j, p.require("TORQUE_LIMIT", j) * torque_unit));
    motor.push_back(cmd(Param::kPwmMax, j, pwm));
    motor.push_back(cmd(Param::kPwmMin, j, -pwm));
    motor.push_back(cmd(Param::kEncRev, j, count_rev));
    if (p.has("ENCODER_DENOMINATOR", j) && device_version >= 10) {
      motor.push_back(cmd(Param::kEncDenominator, j, denominator));
    }
    if (p.has("HALL_DELAY", j) && device_version >= 11) {
      motor.push_back(cmd(Param::kHallDelayFactor, j, std::lround(32768.0 * p.get("HALL_DELAY", j, 0.0) / cycle)));
    }
    groups.push_back(std::move(motor));
  }

  std::vector<Command> velocity;
  for (int j = 0; j < 2; ++j) {
    const auto i = static_cast<std::size_t>(j);
    const double gear = std::fabs(p.require("GEAR", j));
    const double count_rev = p.require("COUNT_REV", j);
    const double ff = 256.0 * 2.0 * M_PI * (1.0 / p.get("TORQUE_FINENESS", j, 1e-6)) / (count_rev * gear);
    velocity.push_back(cmd(Param::kInertiaSelf, j, inertia_self[i] * ff));
    velocity.push_back(cmd(Param::kInertiaCross, j, inertia_cross[i] * ff));
    velocity.push_back(cmd(Param::kPiKp, j, p.require("GAIN_KP", j)));
    velocity.push_back(cmd(Param::kPiKi, j, p.require("GAIN_KI", j)));
    const double integral = p.require("INTEGRAL_MAX", j) * count_rev * gear;
    velocity.push_back(cmd(Param::kIntMax, j, integral));
    velocity.push_back(cmd(Param::kIntMin, j, -integral));
  }
  groups.push_back(std::move(velocity));
  groups.push_back({cmd(Param::kWatchDogLimit, 0, watchdog_ms), cmd(Param::kWatchDogLimit, 1, watchdog_ms)});
  return groups;
}

}  // namespace slamer::tfrog

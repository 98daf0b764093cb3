#include "drivers/wheels/tfrog_text.hpp"

#include <charconv>

namespace slamer::tfrog {

namespace {

// "KEY:value; " -> (KEY, value) with the trailing "; " removed.
bool split_field(const std::string& line, std::string* key, std::string* value) {
  const auto colon = line.find(':');
  if (colon == std::string::npos || colon == 0) {
    return false;
  }
  *key = line.substr(0, colon);
  std::string rest = line.substr(colon + 1);
  while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\r')) {
    rest.pop_back();
  }
  if (!rest.empty() && rest.back() == ';') {
    rest.pop_back();
  }
  *value = rest;
  return true;
}

bool to_int(std::string_view text, int* value) {
  while (!text.empty() && text.front() == ' ') {
    text.remove_prefix(1);
  }
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

bool ReplyCollector::add_line(const std::string& line) {
  switch (stage_) {
    case Stage::kEcho:
      if (line == command_) {
        reply_.echo = line;
        stage_ = Stage::kStatus;
      }
      break;
    case Stage::kStatus:
      reply_.status = line;
      stage_ = line.empty() ? Stage::kDone : Stage::kBody;
      break;
    case Stage::kBody:
      if (line.empty()) {
        stage_ = Stage::kDone;
      } else {
        reply_.body.push_back(line);
      }
      break;
    case Stage::kDone:
      break;
  }
  return complete();
}

std::optional<BoardIdentity> parse_vv(const std::vector<std::string>& body, std::string* error) {
  BoardIdentity identity;
  for (const std::string& line : body) {
    std::string key;
    std::string value;
    if (!split_field(line, &key, &value)) {
      continue;
    }
    if (key == "VEND") {
      identity.vendor = value;
    } else if (key == "PROD") {
      identity.product = value;
    } else if (key == "FIRM") {
      identity.firmware = value;
    } else if (key == "PROT") {
      identity.protocol = value;
    } else if (key == "SERI") {
      identity.serial = value;
    } else if (key == "ID") {
      identity.id = value;
    }
  }
  // PROT is "YPP:<current>:<age>".
  const std::string& prot = identity.protocol;
  const auto second = prot.find(':', 4);
  if (prot.compare(0, 4, "YPP:") != 0 || second == std::string::npos ||
      !to_int(std::string_view(prot).substr(4, second - 4), &identity.protocol_current) ||
      !to_int(std::string_view(prot).substr(second + 1), &identity.protocol_age)) {
    *error = prot.empty() ? "VV reply has no PROT line" : "VV reply has a malformed protocol '" + prot + "'";
    return std::nullopt;
  }
  return identity;
}

bool protocol_compatible(int device_current, int device_age, int host_current, int host_age) {
  return device_current >= host_current - host_age && device_current - device_age <= host_current;
}

std::optional<BoardParameters> parse_pp(const std::vector<std::string>& body, std::string* error) {
  BoardParameters params;
  bool have_pwm = false;
  bool have_motors = false;
  for (const std::string& line : body) {
    std::string key;
    std::string value;
    if (!split_field(line, &key, &value)) {
      continue;
    }
    if (key == "NAME") {
      params.name = value;
    } else if (key == "PWMRES") {
      have_pwm = to_int(value, &params.pwm_resolution) && params.pwm_resolution > 0;
    } else if (key == "MOTORNUM") {
      have_motors = to_int(value, &params.motor_num) && params.motor_num > 0;
    } else if (key == "PARAM") {
      params.param_mode = value;
    }
  }
  if (!have_pwm || !have_motors) {
    *error = std::string("PP reply lacks a valid ") + (!have_pwm ? "PWMRES" : "MOTORNUM");
    return std::nullopt;
  }
  return params;
}

std::string embedded_param_text(const std::vector<std::string>& body) {
  std::string text;
  for (const std::string& line : body) {
    text += line;
    text += '\n';
  }
  return text;
}

}  // namespace slamer::tfrog

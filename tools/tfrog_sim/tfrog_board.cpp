#include "tools/tfrog_sim/tfrog_board.hpp"

#include <algorithm>
#include <cmath>

namespace slamer::tfrog {

TfrogBoard::TfrogBoard(BoardOptions options)
    : options_(std::move(options)), splitter_(512), watchdog_limit_(options_.default_watchdog) {}

int64_t TfrogBoard::count(int motor) const {
  return static_cast<int64_t>(std::floor(position_[static_cast<std::size_t>(motor)]));
}

void TfrogBoard::receive(std::span<const uint8_t> bytes) {
  std::vector<StreamItem> items;
  splitter_.feed(bytes, &items);
  for (const StreamItem& item : items) {
    if (item.kind == StreamItem::Kind::kText) {
      on_line(item.text);
    } else if (item.kind == StreamItem::Kind::kIsochronous || item.kind == StreamItem::Kind::kInterrupt) {
      if (const auto command = parse_command_record(item.raw)) {
        on_command(*command);
      }
    }
  }
}

void TfrogBoard::reply(const std::string& echo, const std::string& status, const std::vector<std::string>& body) {
  std::string text = echo + "\n" + status + "\n";
  for (const std::string& line : body) {
    text += line + "\n";
  }
  text += "\n";
  out_.insert(out_.end(), text.begin(), text.end());
}

void TfrogBoard::on_line(const std::string& line) {
  if (line.empty() || any_servo()) {
    return;  // text runs only with both servos at STOP
  }
  ++text_commands_;
  if (line == "VV") {
    reply(line, "00P",
          {"VEND:" + options_.vendor + "; ", "PROD:" + options_.product + "; ", "FIRM:" + options_.firmware + "; ",
           "PROT:" + options_.protocol + "; ", "SERI:" + options_.serial + "; ", "ID:0; "});
  } else if (line == "PP") {
    reply(line, "00P",
          {"NAME:" + options_.name + "; ", "PWMRES:" + std::to_string(options_.pwm_resolution) + "; ", "MOTORNUM:2; ",
           "DEADTIME:0; ", "PARAM:text; ", "OPTIONS:; ", "INITIODIR:0; ", "INITIODATA:0; ", "SOFTBRAKEMS:0; "});
  } else if (line == "GETEMBEDDEDPARAM") {
    std::vector<std::string> body;
    std::string current;
    for (const char c : options_.embedded_param) {
      if (c == '\n') {
        if (!current.empty()) {
          body.push_back(current);
        }
        current.clear();
      } else {
        current.push_back(c);
      }
    }
    if (!current.empty()) {
      body.push_back(current);
    }
    reply(line, "00P", body);
  } else if (line.rfind("SS", 0) == 0) {
    reply(line, "04T", {});
  } else if (line.rfind("ADMASK", 0) == 0) {
    reply(line, "00P", {});
  } else {
    reply(line, "0Ee", {});
  }
}

void TfrogBoard::on_command(const Command& command) {
  ++commands_;
  watchdog_count_ = 0;
  params_[{command.param, command.motor}] = command.value;
  if (command.motor == kBroadcastMotor) {
    if (command.param == static_cast<uint8_t>(Param::kPing)) {
      const auto record = command_record({static_cast<uint8_t>(Event::kPingResponse), 0, command.value});
      const auto frame = encode_frame(kStartInterrupt, record);
      out_.insert(out_.end(), frame.begin(), frame.end());
    } else if (command.param == static_cast<uint8_t>(Param::kServo)) {
      servo_ = {command.value, command.value};
    }
    return;
  }
  if (command.motor > 1) {
    return;
  }
  const auto m = command.motor;
  switch (static_cast<Param>(command.param)) {
    case Param::kServo:
      servo_[m] = command.value;
      if (command.value != 0) {
        watchdog_expired_ = false;
      }
      break;
    case Param::kWRef:
      w_ref16_[m] = command.value * 16;
      break;
    case Param::kWRefHighPrec:
      w_ref16_[m] = command.value;
      break;
    case Param::kWatchDogLimit:
      watchdog_limit_ = command.value;
      break;
    case Param::kProtocolVersion:
      protocol_version_ = command.value;
      break;
    default:
      break;
  }
}

void TfrogBoard::send_frame() {
  ++frames_;
  if (knobs_.drop_every > 0 && frames_ % knobs_.drop_every == 0) {
    return;
  }
  OdometryFrame frame;
  for (int m = 0; m < 2; ++m) {
    frame.count.push_back(static_cast<int16_t>(static_cast<uint16_t>(count(m) & 0xFFFF)));
    frame.pwm.push_back(static_cast<int16_t>(std::clamp(w_ref16_[static_cast<std::size_t>(m)] / 16, -1000, 1000)));
  }
  auto raw = encode_odometry(frame);
  if (knobs_.wrong_length_every > 0 && frames_ % knobs_.wrong_length_every == 0) {
    raw.resize(raw.size() - 2);
  }
  auto wire = encode_frame(kStartIsochronous, raw);
  if (knobs_.corrupt_every > 0 && frames_ % knobs_.corrupt_every == 0) {
    wire[3] = 0x21;  // a char below 0x40
  }
  out_.insert(out_.end(), wire.begin(), wire.end());
}

void TfrogBoard::step(int ticks) {
  for (int t = 0; t < ticks; ++t) {
    ++ticks_;
    for (std::size_t m = 0; m < 2; ++m) {
      if (servo_[m] == static_cast<int>(ServoLevel::kVelocity)) {
        position_[m] += w_ref16_[m] / 16.0;
      } else {
        position_[m] += pushed_[m];  // free levels and STOP: the wheels turn as pushed
      }
    }
    if (any_servo()) {
      if (++watchdog_count_ >= watchdog_limit_) {
        servo_ = {0, 0};
        w_ref16_ = {0, 0};
        position_ = {0.0, 0.0};
        watchdog_expired_ = true;
        knobs_.error_bits[0] |= kErrorWatchdog;
        knobs_.error_bits[1] |= kErrorWatchdog;
        watchdog_count_ = 0;
      }
      if (ticks_ % 5 == 0 && any_servo()) {
        send_frame();
      }
      if (ticks_ % 200 == 0 && protocol_version_ >= 10) {
        for (int m = 0; m < 2; ++m) {
          if (servo_[static_cast<std::size_t>(m)] >= static_cast<int>(ServoLevel::kTorque)) {
            const auto record = command_record({static_cast<uint8_t>(Event::kErrorState), static_cast<uint8_t>(m),
                                                knobs_.error_bits[static_cast<std::size_t>(m)]});
            const auto frame = encode_frame(kStartInterrupt, record);
            out_.insert(out_.end(), frame.begin(), frame.end());
          }
        }
      }
    }
  }
}

std::vector<uint8_t> TfrogBoard::take_output() {
  std::vector<uint8_t> out;
  out.swap(out_);
  return out;
}

}  // namespace slamer::tfrog

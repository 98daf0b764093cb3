#include "drivers/wheels/tfrog_session.hpp"

#include <algorithm>
#include <cmath>

namespace slamer::tfrog {

namespace {
constexpr int64_t kBannerWait = 100000;   // [us] discard input after "\n\nVV\n\n"
constexpr int64_t kPreludeFlush = 50000;  // [us] "\n\n\n\n", wait, flush input
constexpr int64_t kPreludeSend = 100000;  // [us] then send the command
constexpr int64_t kGroupPause = 20000;    // [us] between parameter groups
constexpr int kVvTries = 3;
constexpr int64_t kFramePeriodCycles = 5;  // odometry every 5 control ticks

int64_t us(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e6));
}
}  // namespace

const char* to_string(LinkState state) {
  switch (state) {
    case LinkState::kClosed:
      return "closed";
    case LinkState::kConnecting:
      return "connecting";
    case LinkState::kRunning:
      return "running";
  }
  return "?";
}

const char* to_string(DriveState state) {
  switch (state) {
    case DriveState::kFree:
      return "free";
    case DriveState::kDriving:
      return "driving";
    case DriveState::kStopped:
      return "stopped";
  }
  return "?";
}

TfrogSession::TfrogSession(SessionOptions options, RobotParams params)
    : options_(options),
      params_(std::move(params)),
      kinematics_(kinematics_from(params_)),
      integrator_(kinematics_),
      clock_(us(kinematics_.cycle) * kFramePeriodCycles, 500) {}

void TfrogSession::opened(int64_t now, bool board_reset) {
  close_reason_.reset();
  splitter_.reset();
  clock_.reset();
  // A re-plugged board has reset itself: its counters restart at 0.
  if (!ever_opened_) {
    unwrapper_.rebase(std::nullopt);
  } else if (board_reset) {
    unwrapper_.rebase(std::array<int16_t, 2>{0, 0});
  } else {
    unwrapper_.rebase_either();
  }
  if (ever_opened_) {
    ++status_.reconnects;
  }
  ever_opened_ = true;
  status_.link = LinkState::kConnecting;
  status_.drive = DriveState::kFree;
  servo_ = ServoLevel::kStop;
  v_ = w_ = target_v_ = target_w_ = 0.0;
  // Make sure the board accepts text commands (they run only at servo STOP).
  send(Param::kServo, 0, 0);
  send(Param::kServo, 1, 0);
  const char banner[] = "\n\nVV\n\n";
  out_.insert(out_.end(), banner, banner + sizeof(banner) - 1);
  step_ = Step::kBanner;
  step_time_ = now;
}

void TfrogSession::closed(const std::string& reason) {
  status_.link = LinkState::kClosed;
  status_.drive = DriveState::kFree;
  status_.last_problem = reason;
  servo_ = ServoLevel::kStop;
  step_ = Step::kDone;
  collector_.reset();
  out_.clear();
}

void TfrogSession::lose_link(const std::string& reason) {
  if (!close_reason_) {
    close_reason_ = reason;
    status_.last_problem = reason;
  }
}

void TfrogSession::send(Param param, uint8_t motor, int32_t value) {
  const auto bytes = encode_command(param, motor, value);
  out_.insert(out_.end(), bytes.begin(), bytes.end());
}

void TfrogSession::set_servo(ServoLevel level, int64_t now) {
  send(Param::kServo, 0, static_cast<int32_t>(level));
  send(Param::kServo, 1, static_cast<int32_t>(level));
  if (level != servo_) {
    servo_since_ = now;
  }
  servo_ = level;
  last_servo_send_ = now;
}

void TfrogSession::start_text(const std::string& command, int64_t now) {
  const char prelude[] = "\n\n\n\n";
  out_.insert(out_.end(), prelude, prelude + sizeof(prelude) - 1);
  text_command_ = command;
  text_phase_ = 0;
  step_ = Step::kTextWait;
  step_time_ = now;
  collector_.reset();
}

void TfrogSession::text_failed(const std::string& why, int64_t now) {
  status_.last_problem = why;
  if (text_command_ == "VV" && ++text_tries_ < kVvTries) {
    start_text("VV", now);
    return;
  }
  lose_link(why);
}

void TfrogSession::on_reply(const TextReply& reply, int64_t now) {
  std::string error;
  if (text_command_ == "VV") {
    auto identity = reply.ok() ? parse_vv(reply.body, &error) : std::nullopt;
    if (!identity) {
      text_failed(reply.ok() ? error : "VV failed with status '" + reply.status + "'", now);
      return;
    }
    if (!protocol_compatible(identity->protocol_current, identity->protocol_age)) {
      status_.identity = *identity;
      text_failed("board protocol " + identity->protocol + " is not compatible with YPP:11:05", now);
      return;
    }
    status_.protocol_warning = identity->protocol_current != kHostProtocolCurrent;
    status_.identity = *identity;
    start_text("PP", now);
  } else if (text_command_ == "PP") {
    auto board = reply.ok() ? parse_pp(reply.body, &error) : std::nullopt;
    if (!board) {
      lose_link(reply.ok() ? error : "PP failed with status '" + reply.status + "'");
      return;
    }
    pwm_max_ = board->pwm_resolution;
    if (options_.use_embedded_param) {
      start_text("GETEMBEDDEDPARAM", now);
      return;
    }
    param_groups_ = connect_parameters(params_, pwm_max_, status_.identity.protocol_current, options_.watchdog_ms);
    param_group_ = 0;
    step_ = Step::kParams;
    step_time_ = now - kGroupPause;
  } else if (text_command_ == "GETEMBEDDEDPARAM") {
    if (!reply.ok()) {
      lose_link("GETEMBEDDEDPARAM failed with status '" + reply.status + "'");
      return;
    }
    try {
      params_ = RobotParams::parse(embedded_param_text(reply.body), "embedded parameters");
      kinematics_ = kinematics_from(params_);
      integrator_ = DiffDriveIntegrator(kinematics_);
      param_groups_ = connect_parameters(params_, pwm_max_, status_.identity.protocol_current, options_.watchdog_ms);
    } catch (const std::exception& e) {
      lose_link(std::string("embedded parameters: ") + e.what());
      return;
    }
    param_group_ = 0;
    step_ = Step::kParams;
    step_time_ = now - kGroupPause;
  }
}

void TfrogSession::received(std::span<const uint8_t> bytes, int64_t now) {
  std::vector<StreamItem> items;
  splitter_.feed(bytes, &items);
  int frames = 0;
  for (const StreamItem& item : items) {
    frames += item.kind == StreamItem::Kind::kIsochronous ? 1 : 0;
  }
  for (const StreamItem& item : items) {
    if (item.kind == StreamItem::Kind::kText) {
      if (step_ == Step::kTextWait && text_phase_ == 2 && collector_ && collector_->add_line(item.text)) {
        const TextReply reply = collector_->reply();
        collector_.reset();
        on_reply(reply, now);
      }
      continue;
    }
    if (item.kind == StreamItem::Kind::kIsochronous) {
      --frames;
    }
    on_frame(item, now, frames);
  }
}

void TfrogSession::on_frame(const StreamItem& item, int64_t now, int frames_behind) {
  if (item.kind == StreamItem::Kind::kBadFrame) {
    ++status_.bad_frames;
    return;
  }
  if (item.kind == StreamItem::Kind::kInterrupt) {
    const auto event = decode_interrupt(item.raw);
    if (!event) {
      return;  // debug dumps are variable length
    }
    if (event->event == static_cast<uint8_t>(Event::kErrorState) && event->motor < 2) {
      const int32_t before = status_.error_bits[event->motor];
      status_.error_bits[event->motor] = event->value;
      if ((event->value & kErrorWatchdog) != 0 && (before & kErrorWatchdog) == 0) {
        unwrapper_.rebase(std::array<int16_t, 2>{0, 0});  // the board cleared its counts
      }
      if (event->value != 0) {
        status_.last_problem = "motor " + std::to_string(event->motor) + " error " + error_bits_text(event->value);
      }
    } else if (event->event == static_cast<uint8_t>(Event::kPingResponse)) {
      ++status_.ping_replies;
    }
    return;
  }
  if (status_.link != LinkState::kRunning) {
    return;  // a stream left over from before the connect
  }
  const auto frame = decode_odometry(item.raw, 2, 0);
  if (!frame) {
    ++status_.wrong_length;
    return;
  }
  last_frame_ = now;
  const FrameStamp stamp = clock_.stamp(now, frames_behind);
  status_.lost_frames += stamp.lost;
  ++status_.frames;
  const double dt = last_frame_utime_ > 0 ? static_cast<double>(stamp.utime - last_frame_utime_) * 1e-6 : 0.0;
  last_frame_utime_ = stamp.utime;
  const auto delta = unwrapper_.feed({frame->count[0], frame->count[1]});
  integrator_.add(delta, dt);
  samples_.push_back(
      OdometrySample{stamp.utime, integrator_.pose(), integrator_.v(), integrator_.omega(), unwrapper_.cumulative()});
}

std::array<int32_t, 2> TfrogSession::wheel_values(double v, double omega) const {
  const double half = omega * kinematics_.tread / 2.0;
  const std::array<double, 2> wheel_rad_s = {(v + half) / kinematics_.radius[0], (v - half) / kinematics_.radius[1]};
  std::array<int32_t, 2> values{};
  for (std::size_t i = 0; i < 2; ++i) {
    const double counts_per_cycle =
        wheel_rad_s[i] * kinematics_.counts_per_wheel_rev[i] * kinematics_.cycle / (2.0 * M_PI);
    values[i] = static_cast<int32_t>(std::lround(counts_per_cycle * (options_.high_resolution ? 16.0 : 1.0)));
  }
  return values;
}

void TfrogSession::command(double v, double omega, int64_t now) {
  if (!std::isfinite(v) || !std::isfinite(omega)) {
    ++status_.rejected_commands;
    status_.last_problem = "rejected a non-finite velocity command";
    return;
  }
  if (status_.link != LinkState::kRunning) {
    return;  // nothing drives until the board is connected
  }
  target_v_ = std::clamp(v, -kinematics_.max_vel, kinematics_.max_vel);
  target_w_ = std::clamp(omega, -kinematics_.max_w, kinematics_.max_w);
  last_command_ = now;
  if (status_.drive != DriveState::kDriving) {
    status_.drive = DriveState::kDriving;
    last_cycle_ = now;
    set_servo(ServoLevel::kVelocity, now);
  }
}

void TfrogSession::control_cycle(int64_t now) {
  const double dt = std::clamp(static_cast<double>(now - last_cycle_) * 1e-6, 0.0, 2.0 * options_.control_cycle);
  last_cycle_ = now;
  if (status_.drive == DriveState::kDriving) {
    const double dv = kinematics_.max_acc_v * dt;
    const double dw = kinematics_.max_acc_w * dt;
    v_ = std::clamp(target_v_, v_ - dv, v_ + dv);
    w_ = std::clamp(target_w_, w_ - dw, w_ + dw);
  } else {
    v_ = w_ = 0.0;
  }
  if (status_.drive == DriveState::kStopped && options_.timeout_servo_stop && servo_ == ServoLevel::kStop &&
      now - stopped_at_ >= us(0.5)) {
    set_servo(options_.free_level, now);  // stopped: let the board stream again
  } else if (now - last_servo_send_ >= us(options_.mode_resend)) {
    set_servo(servo_, now);
  }
  // The wheel velocity is sent every cycle in every state: it feeds the watchdog.
  const auto values = wheel_values(v_, w_);
  const Param param = options_.high_resolution ? Param::kWRefHighPrec : Param::kWRef;
  send(param, 0, values[0]);
  send(param, 1, values[1]);
}

void TfrogSession::tick(int64_t now) {
  if (status_.link == LinkState::kClosed || close_reason_) {
    return;
  }
  if (step_ == Step::kBanner && now - step_time_ >= kBannerWait) {
    splitter_.reset();
    text_tries_ = 0;
    start_text("VV", now);
  } else if (step_ == Step::kTextWait) {
    if (text_phase_ == 0 && now - step_time_ >= kPreludeFlush) {
      splitter_.reset();  // flush input
      text_phase_ = 1;
    } else if (text_phase_ == 1 && now - step_time_ >= kPreludeSend) {
      splitter_.reset();
      const std::string line = text_command_ + "\n";
      out_.insert(out_.end(), line.begin(), line.end());
      collector_ = std::make_unique<ReplyCollector>(text_command_);
      text_phase_ = 2;
      step_time_ = now;
    } else if (text_phase_ == 2 && now - step_time_ >= us(options_.reply_timeout)) {
      text_failed("no reply to " + text_command_, now);
    }
  } else if (step_ == Step::kParams && now - step_time_ >= kGroupPause) {
    if (param_group_ < param_groups_.size()) {
      for (const Command& command : param_groups_[param_group_]) {
        const auto bytes = encode_command(command);
        out_.insert(out_.end(), bytes.begin(), bytes.end());
      }
      ++param_group_;
      step_time_ = now;
    } else {
      step_ = Step::kDone;
      status_.link = LinkState::kRunning;
      last_frame_ = now;
      last_cycle_ = now;
      next_cycle_ = now;
      set_servo(options_.free_level, now);
    }
  }
  if (status_.link != LinkState::kRunning) {
    return;
  }
  // Command timeout: velocity 0 (or servo STOP) at once, no ramp.
  if (status_.drive == DriveState::kDriving && now - last_command_ > us(options_.cmd_timeout)) {
    status_.drive = DriveState::kStopped;
    stopped_at_ = now;
    v_ = w_ = target_v_ = target_w_ = 0.0;
    if (options_.timeout_servo_stop) {
      set_servo(ServoLevel::kStop, now);
    } else {
      const Param param = options_.high_resolution ? Param::kWRefHighPrec : Param::kWRef;
      send(param, 0, 0);
      send(param, 1, 0);
    }
    status_.last_problem = "velocity commands timed out: stopped";
  }
  if (now >= next_cycle_) {
    control_cycle(now);
    next_cycle_ = std::max(next_cycle_ + us(options_.control_cycle), now);
  }
  if (servo_ != ServoLevel::kStop && now - servo_since_ > us(options_.silence_timeout) &&
      now - last_frame_ > us(options_.silence_timeout)) {
    lose_link("no frames from the board for " + std::to_string(options_.silence_timeout) + " s");
  }
}

void TfrogSession::stop_servos() {
  send(Param::kServo, 0, 0);
  send(Param::kServo, 1, 0);
  servo_ = ServoLevel::kStop;
}

std::vector<uint8_t> TfrogSession::take_output() {
  std::vector<uint8_t> out;
  out.swap(out_);
  return out;
}

std::vector<OdometrySample> TfrogSession::take_samples() {
  std::vector<OdometrySample> out;
  out.swap(samples_);
  return out;
}

}  // namespace slamer::tfrog

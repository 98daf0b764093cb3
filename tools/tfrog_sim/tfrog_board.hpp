// A T-frog TF-2MD3-R6 board model speaking the real byte protocol
// (../shared/protocols/tfrog.md): text commands (VV, PP, GETEMBEDDEDPARAM, SS,
// ADMASK) only while both servos are STOP, binary parameter commands, servo
// levels, the watchdog (any valid binary command resets it; at the limit both
// servos STOP, WATCHDOG error, counts cleared), odometry frames every 5 ticks
// only while a servo is active (int16 counts that wrap), error-state reports
// every 200 ticks (protocol_version >= 10, servo >= TORQUE), ping replies.
// Wheels follow w_ref in VELOCITY; in other levels they move as pushed
// (set_pushed). Knobs: corrupt / drop / wrong-length frames, error bits.
// Pure: the caller advances time in 1 ms control ticks.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "drivers/wheels/tfrog_codec.hpp"

namespace slamer::tfrog {

struct BoardOptions {
  std::string vendor = "T-frog Project";
  std::string product = "T-frog Motor Driver rev.5";
  std::string firmware = "fcf3734";
  std::string protocol = "YPP:11:02";
  std::string serial = "01300000";
  std::string name = "icart-mini";
  int pwm_resolution = 1000;
  std::string embedded_param;  // GETEMBEDDEDPARAM body
  int default_watchdog = 600;  // [ticks]
};

struct BoardKnobs {
  int corrupt_every = 0;       // damage one char of every Nth frame (0: never)
  int drop_every = 0;          // skip every Nth frame
  int wrong_length_every = 0;  // send every Nth frame one word short
  std::array<int32_t, 2> error_bits{};
};

class TfrogBoard {
 public:
  explicit TfrogBoard(BoardOptions options = {});

  void receive(std::span<const uint8_t> bytes);
  void step(int ticks = 1);  // 1 ms each
  std::vector<uint8_t> take_output();

  // Wheel motion in non-VELOCITY levels [motor counts per tick].
  void set_pushed(const std::array<double, 2>& counts_per_tick) { pushed_ = counts_per_tick; }
  BoardKnobs& knobs() { return knobs_; }

  int servo(int motor) const { return servo_[static_cast<std::size_t>(motor)]; }
  // Commanded speed in 1/16 counts per tick (param 0 values are stored x16).
  int32_t w_ref16(int motor) const { return w_ref16_[static_cast<std::size_t>(motor)]; }
  int64_t count(int motor) const;
  int watchdog_limit() const { return watchdog_limit_; }
  bool watchdog_expired() const { return watchdog_expired_; }
  int64_t ticks() const { return ticks_; }
  int64_t frames_sent() const { return frames_; }
  int64_t commands_received() const { return commands_; }
  // Last value received for (param, motor).
  const std::map<std::pair<int, int>, int32_t>& params() const { return params_; }
  int64_t text_commands() const { return text_commands_; }

 private:
  void on_line(const std::string& line);
  void on_command(const Command& command);
  void reply(const std::string& echo, const std::string& status, const std::vector<std::string>& body);
  void send_frame();
  bool any_servo() const { return servo_[0] != 0 || servo_[1] != 0; }

  BoardOptions options_;
  BoardKnobs knobs_;
  StreamSplitter splitter_;
  std::vector<uint8_t> out_;
  std::array<int, 2> servo_{};
  std::array<int32_t, 2> w_ref16_{};
  std::array<double, 2> position_{};  // [counts]
  std::array<double, 2> pushed_{};
  int watchdog_limit_;
  int watchdog_count_ = 0;
  bool watchdog_expired_ = false;
  int protocol_version_ = 0;
  int64_t ticks_ = 0;
  int64_t frames_ = 0;
  int64_t commands_ = 0;
  int64_t text_commands_ = 0;
  std::map<std::pair<int, int>, int32_t> params_;
};

}  // namespace slamer::tfrog

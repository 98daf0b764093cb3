// The driver's conversation with one T-frog board, without I/O: bytes in,
// bytes out, time passed in.
//
// Connect (tfrog.md sections 5-6): servo STOP, "\n\nVV\n\n", VV (3 tries,
// YPP version check), PP, optionally GETEMBEDDEDPARAM, the parameters YP-Spur
// sends (ypspur_params.hpp), then a free servo level so the board streams.
// Running: odometry frames -> OdometrySample; every control cycle the wheel
// velocity is re-sent (w_ref 0 while free), which feeds the board's 300 ms
// watchdog. A velocity command switches both motors to VELOCITY (3) and is
// turned into wheel speeds within the speed/acceleration limits; cmd_timeout
// after the last one both motors get velocity 0 (or servo STOP) at once and
// stay stopped until a new command. Unplug (the caller reports a read error)
// or 0.3 s of silence while servoed -> should_close(); the caller reopens the
// same path and calls opened() again; ticks and pose continue without a jump.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "drivers/wheels/tfrog_codec.hpp"
#include "drivers/wheels/tfrog_text.hpp"
#include "drivers/wheels/wheel_odometry.hpp"
#include "drivers/wheels/ypspur_params.hpp"

namespace slamer::tfrog {

struct SessionOptions {
  ServoLevel free_level = ServoLevel::kCounter;  // counter, torque or open-free
  bool high_resolution = true;                   // w_ref_highprec (param 1, 16x) instead of param 0
  int watchdog_ms = 300;                         // board watchdog while running
  double control_cycle = 0.02;                   // [s] between wheel velocity commands
  double cmd_timeout = 0.2;                      // [s] after the last command: stop
  bool timeout_servo_stop = false;               // stop by servo STOP instead of velocity 0
  double silence_timeout = 0.3;                  // [s] without frames while servoed: link lost
  double reply_timeout = 0.3;                    // [s] per text command
  bool use_embedded_param = false;               // read the robot parameters from the board
  double mode_resend = 1.0;                      // [s] between servo level re-sends
};

enum class LinkState { kClosed, kConnecting, kRunning };
enum class DriveState { kFree, kDriving, kStopped };
const char* to_string(LinkState state);
const char* to_string(DriveState state);

struct OdometrySample {
  int64_t utime = 0;
  Pose2 pose;
  double v = 0.0;
  double omega = 0.0;
  std::array<int64_t, 2> ticks{};  // cumulative raw motor counts, [0] motor 0 (right), [1] motor 1 (left)
};

struct SessionStatus {
  LinkState link = LinkState::kClosed;
  DriveState drive = DriveState::kFree;
  BoardIdentity identity;
  bool protocol_warning = false;  // compatible but not the same version
  int64_t frames = 0;
  int64_t lost_frames = 0;
  int64_t bad_frames = 0;    // undecodable binary frames
  int64_t wrong_length = 0;  // odometry frames of the wrong length
  int64_t reconnects = 0;
  int64_t ping_replies = 0;
  int64_t rejected_commands = 0;  // non-finite velocity commands
  std::array<int32_t, 2> error_bits{};
  std::string last_problem;  // one line
};

class TfrogSession {
 public:
  TfrogSession(SessionOptions options, RobotParams params);

  // board_reset: the device had vanished (unplugged), so the board restarted its counters at 0.
  void opened(int64_t now, bool board_reset = true);
  void closed(const std::string& reason);
  void received(std::span<const uint8_t> bytes, int64_t now);
  // A velocity command [m/s], [rad/s].
  void command(double v, double omega, int64_t now);
  // Call often (every few ms): timers, control cycle, timeouts.
  void tick(int64_t now);
  // Servo STOP on both motors (append to output); call before exit.
  void stop_servos();

  std::vector<uint8_t> take_output();
  std::vector<OdometrySample> take_samples();
  bool should_close() const { return close_reason_.has_value(); }
  const std::string& close_reason() const { return *close_reason_; }
  const SessionStatus& status() const { return status_; }
  ServoLevel servo_level() const { return servo_; }
  const Kinematics& kinematics() const { return kinematics_; }
  // Wheel velocity command values (param 0 or 1 units) for v, omega.
  std::array<int32_t, 2> wheel_values(double v, double omega) const;

 private:
  enum class Step { kBanner, kTextWait, kParams, kDone };
  void start_text(const std::string& command, int64_t now);
  void on_reply(const TextReply& reply, int64_t now);
  void text_failed(const std::string& why, int64_t now);
  void on_frame(const StreamItem& item, int64_t now, int frames_behind);
  void send(Param param, uint8_t motor, int32_t value);
  void set_servo(ServoLevel level, int64_t now);
  void control_cycle(int64_t now);
  void lose_link(const std::string& reason);

  SessionOptions options_;
  RobotParams params_;
  Kinematics kinematics_;
  SessionStatus status_;
  StreamSplitter splitter_;
  TickUnwrapper unwrapper_;
  DiffDriveIntegrator integrator_;
  FrameClock clock_;
  std::vector<uint8_t> out_;
  std::vector<OdometrySample> samples_;
  std::optional<std::string> close_reason_;
  bool ever_opened_ = false;

  // Connect sequence.
  Step step_ = Step::kDone;
  std::string text_command_;
  int text_phase_ = 0;  // 0: prelude sent, 1: input flushed, 2: command sent
  int text_tries_ = 0;
  int64_t step_time_ = 0;
  std::unique_ptr<ReplyCollector> collector_;
  int pwm_max_ = 0;
  std::vector<std::vector<Command>> param_groups_;
  std::size_t param_group_ = 0;

  // Running.
  ServoLevel servo_ = ServoLevel::kStop;
  int64_t servo_since_ = 0;
  int64_t last_servo_send_ = 0;
  int64_t last_frame_ = 0;
  int64_t last_frame_utime_ = 0;
  int64_t next_cycle_ = 0;
  int64_t last_cycle_ = 0;
  int64_t last_command_ = 0;
  int64_t stopped_at_ = 0;
  double target_v_ = 0.0;
  double target_w_ = 0.0;
  double v_ = 0.0;
  double w_ = 0.0;
};

}  // namespace slamer::tfrog

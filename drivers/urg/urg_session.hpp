// The SCIP 2.0 session with one URG sensor (issue 13 "Session and transports"):
// bytes in, bytes out, time passed in; no I/O. On every connection:
//   QT (stop streaming; data arriving before the echo is drained; "0Ee" -> TM2
//   to leave time-adjust mode; a 1-char SCIP 1.1 status -> "SCIP2.0"), VV, PP
//   (geometry, re-read after every reconnect), II, TM0 + a burst of TM1 + TM2
//   (clock offset), BM, then continuous MD or ME. While streaming, TM1 between
//   scans keeps the clock model current without stopping the stream.
// Laser malfunction statuses -> RS and start again; after repeated failures
// -> RB twice within 1 s (the sensor reboots; the caller reconnects).
// Silence for 3 scan periods, or replies that never come -> should_disconnect().
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/sensors/laser_scan.hpp"
#include "drivers/urg/clock_model.hpp"
#include "drivers/urg/scip_reply.hpp"
#include "drivers/urg/scip_scan.hpp"

namespace slamer::urg {

struct UrgSessionOptions {
  int first_step = -1;  // -1: the sensor's AMIN
  int last_step = -1;   // -1: the sensor's AMAX
  int cluster = 1;
  bool intensities = false;  // ME instead of MD
  std::string frame = "laser";
  int sync_samples = 40;               // TM1 round trips in the start-up burst (0: no TM0/TM1/TM2)
  double tm1_while_streaming_hz = 20;  // 0: never
  double reply_timeout_s = 1.0;
  int retries = 2;               // resends of a command that got no reply, before giving up
  int silence_periods = 3;       // scan periods without data -> reconnect
  int resets_before_reboot = 2;  // RS this many times in a row, then RB
  ClockModelOptions clock;
};

struct SessionCounters {
  int64_t scans = 0;           // published
  int64_t checksum = 0;        // scans refused: a failed checksum
  int64_t truncated = 0;       // scans refused: a data line missing
  int64_t length = 0;          // scans refused: wrong number of values or line length
  int64_t bad_char = 0;        // scans refused: a char outside the encoding
  int64_t command_errors = 0;  // error statuses to our commands
  int64_t malfunctions = 0;    // laser/hardware statuses
  int64_t resets = 0;          // RS sent
  int64_t reboots = 0;         // RB pairs sent
  int64_t timeouts = 0;        // commands without reply
  int64_t silences = 0;        // streams that went quiet
  int64_t stray = 0;           // replies to nothing we asked (drained)
  int64_t overflows = 0;       // replies too long to frame
  int64_t scip1_switches = 0;  // SCIP 1.1 -> 2.0 switches
  int64_t connects = 0;
};

class UrgSession {
 public:
  enum class State {
    kDisconnected,
    kProbe,
    kScip2,
    kLeaveTimeAdjust,
    kVersion,
    kParams,
    kInfo,
    kTimeAdjustOn,
    kSync,
    kTimeAdjustOff,
    kLaserOn,
    kStartScan,
    kStreaming,
    kReset,
    kReboot,
    kRebooted
  };

  explicit UrgSession(UrgSessionOptions options);

  void connected(int64_t now_us);
  void received(std::string_view bytes, int64_t now_us);
  void tick(int64_t now_us);
  void disconnected();

  std::string take_output();            // bytes to write now
  std::vector<LaserScan> take_scans();  // scans completed since the last call
  bool should_disconnect() const { return disconnect_; }
  // True once the probe got no answer at all (the serial baud rate may be wrong).
  bool probe_unanswered() const { return probe_unanswered_; }

  State state() const { return state_; }
  const char* state_name() const;
  bool streaming() const { return state_ == State::kStreaming; }
  const SessionCounters& counters() const { return counters_; }
  const SensorGeometry& geometry() const { return geometry_; }
  const std::string& model() const { return model_; }
  const std::string& serial() const { return serial_; }
  const std::string& last_error() const { return last_error_; }
  const ClockModel& clock() const { return clock_; }

 private:
  void send(std::string_view command, int64_t now_us, std::string_view tag = {});
  void handle(const Reply& reply, int64_t now_us);
  void handle_scan(const Reply& reply, int64_t now_us);
  void start_stream(int64_t now_us);
  void fail(const std::string& why, bool malfunction, int64_t now_us);
  void restart(int64_t now_us);
  void error(const std::string& text) { last_error_ = text; }

  UrgSessionOptions options_;
  State state_ = State::kDisconnected;
  ReplyFramer framer_;
  std::string output_;
  std::vector<LaserScan> scans_;
  SessionCounters counters_;
  SensorGeometry geometry_;
  std::string model_, serial_, last_error_;
  ClockModel clock_;
  StampUnwrapper unwrap_;
  std::string pending_;  // command whose reply we wait for ("" = none)
  std::string pending_line_;
  int64_t deadline_us_ = 0;
  int retries_left_ = 0;
  int64_t last_data_us_ = 0;
  int64_t next_tm1_us_ = 0;
  bool tm1_streaming_ok_ = true;
  int tm1_in_flight_ = 0;
  int64_t tm1_seq_ = 0;
  std::vector<int64_t> tm1_send_us_;  // by tag number, for the in-flight TM1s
  std::vector<SyncSample> burst_;
  int consecutive_failures_ = 0;
  int64_t first_rb_us_ = 0;
  int64_t scan_seq_ = 0;
  bool disconnect_ = false;
  bool probe_unanswered_ = false;
  bool probe_answered_ = false;
  int start_step_ = 0, end_step_ = 0;
};

}  // namespace slamer::urg

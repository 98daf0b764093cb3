// A SCIP 2.0 sensor, for slamer-urg-sim (issue 13 "The emulator"): the state
// machine (idle, scanning, time-adjust, error; SCIP 1.1 at power-up for the
// URG-04LX), models of URM-40LC, UST-10LX, UTM-30LX and URG-04LX, a device
// clock with offset and drift, scans of a fixed scene or fed from outside
// (feed(): each sent as the real sensor would, after its last requested beam,
// stamped by the device clock at its first), and fault knobs. Pure: commands
// and host times in, timed reply bytes out; the program does the I/O.
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <string_view>
#include <vector>

namespace slamer::urg {

struct SimModel {
  std::string name;  // MODL
  int dmin = 20, dmax = 30000, ares = 1440, amin = 0, amax = 1080, afrt = 540, scan_rpm = 2400;
  bool scip1_at_power_up = false;
  bool tm_on_5ms_ticks = false;  // UUST2-like firmware
  bool intensities = true;
  std::string serial = "H0000001";
};
// "URM-40LC", "UST-10LX", "UTM-30LX", "URG-04LX"; false if unknown.
bool sim_model(const std::string& name, SimModel* model);

struct SimKnobs {
  double delay_ms = 0.0;              // transport delay of every reply
  double jitter_ms = 0.0;             // + uniform [0, jitter] per reply
  double drift_ppm = 0.0;             // device clock rate - 1
  double offset_ms = 12345.0;         // device clock at host time 0 of the power-up
  bool tm_on_5ms_ticks = false;       // force TM1 replies onto 5 ms device ticks
  double bad_checksum_rate = 0;       // per scan
  double truncate_rate = 0;           // per scan: a data line missing
  double garbage_rate = 0;            // per scan: garbage bytes before it
  std::string error_status;           // e.g. "50": scans fail with it after error_after scans
  int error_after = -1;               // -1: never
  bool error_survives_reset = false;  // RS does not clear the error; RB does
  std::string model_after_reboot;     // a different model (geometry) after RB
  bool external_scans = false;        // scans only from feed(), none of the fixed scene
  unsigned seed = 1;
};

// A scan from outside (sim_scan_source.hpp): device values for steps AMIN..AMAX.
struct SimScan {
  int64_t first_beam_us = 0;          // host time of step AMIN's beam
  int64_t received_us = 0;            // when the emulator got it: it is never sent earlier
  std::vector<uint32_t> values;       // [mm] or error codes
  std::vector<uint32_t> intensities;  // empty: the emulator makes some up
};

struct SimTruth {
  uint32_t device_stamp_ms = 0;  // as sent (24 bit)
  int64_t first_beam_host_us = 0;
  int64_t sent_host_us = 0;  // when the reply left the sensor (before transport delay)
};

class SimSensor {
 public:
  SimSensor(SimModel model, SimKnobs knobs);

  void power_on(int64_t host_us);
  void receive(std::string_view bytes, int64_t host_us);
  // Generates what is due up to host_us and returns the bytes that arrive at
  // the host by then (in order).
  std::string poll(int64_t host_us);
  // With knobs.external_scans: a scan to send while streaming (dropped when
  // not streaming, or when it began before the MD/ME command, as a real sensor
  // only sends rotations measured after it).
  void feed(SimScan scan);
  int64_t next_event_us() const;  // host time of the next reply or scan, INT64_MAX if none
  bool reboot_requested();        // an RB pair: the program drops the connection, then power_on()
  std::vector<SimTruth> take_truth();
  const SimModel& model() const { return model_; }
  bool scanning() const { return state_ == State::kScanning; }
  int64_t scans_sent() const { return scans_sent_; }
  // The scene's true range of a step [mm] (before clamping to DMIN..DMAX).
  double range_mm(int step) const;
  // Steps that return "no echo" (a window in the scene).
  static bool no_echo_step(int step) { return step % 97 == 13; }

 private:
  enum class State { kIdle, kScanning, kTimeAdjust, kError };
  void command(const std::string& line, int64_t host_us);
  void reply(int64_t ready_us, const std::string& bytes);
  std::string status_reply(const std::string& echo, const std::string& status, const std::string& body = {});
  std::string kv(const std::string& key, const std::string& value) const;
  double device_ms(int64_t host_us) const;
  // When the reply of a scan whose requested steps start at `first_beam_us` is ready.
  int64_t scan_ready_us(int64_t first_beam_us) const;
  void emit_scan(int64_t first_beam_us, int64_t ready_us, const SimScan* source);
  bool count_scan_fails(int64_t ready_us);  // the error_after knob; true: the laser failed now
  void poll_external(int64_t host_us);

  SimModel model_;
  SimModel model_after_reboot_;
  SimKnobs knobs_;
  std::mt19937 rng_;
  State state_ = State::kIdle;
  bool scip1_ = false;
  bool laser_on_ = false;
  int64_t power_on_us_ = 0;
  std::string input_;
  struct Out {
    int64_t due_us;
    std::string bytes;
  };
  std::deque<Out> out_;
  int64_t last_due_us_ = 0;
  // Streaming.
  bool intensity_ = false;
  int start_ = 0, end_ = 0, cluster_ = 1, skip_ = 0, remaining_ = 0;
  std::string scan_echo_;
  int64_t next_scan_us_ = 0;
  int64_t streaming_since_us_ = 0;  // when the MD/ME command arrived
  int64_t rotation_ = 0;            // external scans seen while streaming (for the skip field)
  std::deque<SimScan> fed_;
  int64_t scans_sent_ = 0;
  int64_t scans_total_ = 0;
  bool error_latched_ = false;
  int rb_count_ = 0;
  int64_t rb_first_us_ = 0;
  bool reboot_ = false;
  std::vector<SimTruth> truth_;
};

}  // namespace slamer::urg

// The sensor clock model: maps the URG's 1 ms device clock to host time
// (issue 13 "Timestamps"; scip.md "TM (time adjust) and the 24-bit clock").
//
// - StampUnwrapper turns the 24-bit millisecond counter into a monotonic count
//   (half-range rule; it wraps every 2^24 ms = 4.66 h).
// - ClockModel: host(x) = anchor_host + gain * (x - anchor_device), x in device us.
//   The offset comes from TM1 round trips: each (send, receive, device ms d)
//   says the device clock read d at some host time in [send, receive], so
//   host(d) <= receive and host(d + 1 ms) > send; the intersection of these
//   intervals over the burst (narrowest for the fastest round trips) gives the
//   offset to well under a millisecond. TM1 sent between scans while streaming
//   (real sensors answer it outside time-adjust mode) keeps adding samples; over
//   a long window the feasible (offset, gain) region also gives the gain. The gain (drift) is then kept current
//   while streaming from the scans alone: (arrival - device time) has a lower
//   envelope whose slope is gain - 1 (minimum-delay tracking: a line through
//   the minimum lags of a few spans of the stream), so no re-sync stops the stream. The first beam's device time
//   is refined below the 1 ms stamp resolution by fitting the stamps of recent
//   scans to a constant period (set membership: the phase walks through the
//   millisecond grid). A sensor whose period is a whole number of device ms
//   keeps its phase hidden: then the stamp's middle is used (<= 0.5 ms off).
// Pure: every time is passed in.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

namespace slamer::urg {

class StampUnwrapper {
 public:
  // Device ms (24-bit) -> unwrapped device ms, monotonic across wraps.
  int64_t unwrap(uint32_t raw_ms);
  void reset() { started_ = false; }

 private:
  bool started_ = false;
  uint32_t last_ = 0;
  int64_t unwrapped_ = 0;
};

struct ClockModelOptions {
  int phase_window = 1200;             // scans in the first-beam phase fit (30 s at 40 Hz)
  int drift_every = 20;                // scans between drift updates
  int min_drift_points = 40;           // scans before the drift is estimated
  int max_drift_points = 48000;        // scans kept for the drift (20 min at 40 Hz)
  double max_gain_error = 2e-4;        // |gain - 1| beyond this is refused (200 ppm)
  int max_sync_samples = 1200;         // TM1 round trips kept (60 s at 20 Hz)
  double min_gain_span_s = 5.0;        // TM1 samples must span this long to give the gain
  int64_t offset_window_us = 5000000;  // samples used for the offset before the gain is known
};

struct SyncSample {
  int64_t send_us = 0;     // host time the TM1 left
  int64_t receive_us = 0;  // host time its reply arrived
  int64_t device_ms = 0;   // unwrapped device time in the reply
};

class ClockModel {
 public:
  explicit ClockModel(ClockModelOptions options = {}) : options_(options) {}

  // Offset from a burst of TM1 round trips; false if none is usable. Keeps the gain.
  bool sync(const std::vector<SyncSample>& samples);
  // One more TM1 round trip (e.g. sent between scans while streaming): the
  // offset and gain are refitted over the recent samples.
  void add_sync_sample(const SyncSample& sample);
  // A new connection: forget the scan history (the gain is kept: same crystal).
  void reset_stream();

  // One scan: its device stamp (unwrapped ms) and the host arrival time of the
  // reply. Returns the host time of the first beam [us]. Without a sync the
  // first scan's arrival anchors the clock (late by the transport delay).
  int64_t scan_utime(int64_t device_ms, int64_t scan_period_us, int64_t arrival_us);

  int64_t host_of_device(double device_us) const;
  bool synced() const { return synced_; }
  double gain() const { return gain_; }
  double drift_ppm() const { return (gain_ - 1.0) * 1e6; }
  double sync_width_us() const { return sync_width_us_; }  // width of the offset interval
  int64_t sync_count() const { return sync_count_; }
  std::size_t sync_samples() const { return sync_samples_.size(); }

 private:
  struct Stamp {
    int64_t index;
    int64_t device_ms;
  };
  struct LagPoint {
    double device_us;
    double lag_us;  // (arrival - device time) - lag_reference_us_
  };
  double first_beam_device_us(int64_t device_ms, int64_t scan_period_us);
  void track_drift(double device_us, int64_t arrival_us);
  void fit_phase(double nominal_ms);
  void fit_sync();
  void re_anchor(double device_us);

  ClockModelOptions options_;
  bool synced_ = false;
  bool anchored_ = false;
  double anchor_device_us_ = 0;
  int64_t anchor_host_us_ = 0;
  double gain_ = 1.0;
  double sync_width_us_ = 0;
  int64_t sync_count_ = 0;
  std::deque<SyncSample> sync_samples_;
  bool gain_from_sync_ = false;
  int since_gain_fit_ = 0;
  // Phase fit.
  std::deque<Stamp> stamps_;
  int64_t next_index_ = 0;
  double period_ms_ = 0;  // fitted scan period [device ms], 0 = none
  double phase_ms_ = 0;   // fitted device time of scan phase_index_ [ms]
  int64_t phase_index_ = 0;
  int since_phase_fit_ = 0;
  // Drift: lower envelope of (arrival - device), relative to lag_reference_.
  std::deque<LagPoint> lags_;
  int since_drift_update_ = 0;
  bool lag_reference_set_ = false;
  double lag_reference_us_ = 0;
};

}  // namespace slamer::urg

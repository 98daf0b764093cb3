// Wheel odometry of a differential-drive base from two encoder streams.
//
// TickUnwrapper turns a board's int16 absolute counts into cumulative int64
// ticks: delta = (int16)(count - previous) per frame (tfrog.md section 4), and
// after a board restart (replug, watchdog clear) re-anchors at 0 so the
// cumulative ticks continue without a jump.
// DiffDriveIntegrator turns tick deltas into a pose with per-wheel signed radii
// (i-Cart mini: motor 0 right +0.07455, motor 1 left -0.07455, tfrog.md
// section 10): travel_i = 2 pi R_i d_i / counts_per_rev_i, ds = (r + l) / 2,
// dtheta = (r - l) / tread, integrated exactly on the arc (SE(2) exponential)
// or, as YP-Spur does, with a first-order step (kEuler) for comparison.
// FrameClock stamps frames: arrival minus the half USB frame and the frames
// still queued behind it, filtered against the fixed frame period; a gap is
// counted as lost frames once the following frames stay a period late (a
// single late read is not a loss; the frames around a loss are stamped up to
// a period early). Pure: time is passed in.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "common/geometry/se2.hpp"
#include "drivers/wheels/ypspur_params.hpp"

namespace slamer::tfrog {

class TickUnwrapper {
 public:
  // Feeds one frame's raw counts; returns the per-motor deltas.
  std::array<int64_t, 2> feed(const std::array<int16_t, 2>& raw);
  // The next frame is measured from `anchor` (0 after a board restart); nullopt: from itself.
  void rebase(std::optional<std::array<int16_t, 2>> anchor) {
    previous_ = anchor;
    either_ = false;
  }
  // Unknown whether the board restarted (a reconnect without an unplug; its
  // watchdog may have cleared the counts): the next frame is measured from
  // the previous count or from 0, whichever gives the smaller motion.
  void rebase_either() { either_ = previous_.has_value(); }
  const std::array<int64_t, 2>& cumulative() const { return cumulative_; }

 private:
  std::optional<std::array<int16_t, 2>> previous_;
  bool either_ = false;
  std::array<int64_t, 2> cumulative_{};
};

enum class Integration { kExactArc, kEuler };

class DiffDriveIntegrator {
 public:
  explicit DiffDriveIntegrator(const Kinematics& kinematics, Integration integration = Integration::kExactArc)
      : k_(kinematics), integration_(integration) {}
  // Adds motor deltas [ticks] over dt [s] (dt <= 0: pose only, speeds kept).
  void add(const std::array<int64_t, 2>& delta, double dt);
  const Pose2& pose() const { return pose_; }
  double v() const { return v_; }
  double omega() const { return omega_; }
  double distance() const { return distance_; }  // total |travel| of the base [m]
  // Travel of motor i [m], forward-positive (the signed radius applied).
  double travel(int motor, int64_t ticks) const;

 private:
  Kinematics k_;
  Integration integration_;
  Pose2 pose_;
  double v_ = 0.0;
  double omega_ = 0.0;
  double distance_ = 0.0;
};

struct FrameStamp {
  int64_t utime = 0;
  int64_t lost = 0;  // frames missing before this one
};

class FrameClock {
 public:
  // period_us: 5 control cycles; latency_us: subtracted from arrival (half USB frame).
  explicit FrameClock(int64_t period_us = 5000, int64_t latency_us = 500) : period_(period_us), latency_(latency_us) {}
  // A frame completed in a read that arrived at receive_utime, with
  // `frames_behind` more complete frames in the same read after it.
  FrameStamp stamp(int64_t receive_utime, int frames_behind);
  void reset() {
    last_.reset();
    late_frames_ = 0;
  }
  int64_t lost_total() const { return lost_total_; }

 private:
  int64_t period_;
  int64_t latency_;
  static constexpr int kConfirm = 4;
  std::optional<int64_t> last_;
  int64_t lost_total_ = 0;
  int late_frames_ = 0;
  int64_t min_late_ = 0;
};

}  // namespace slamer::tfrog

// Simulates the i-Cart mini driving its scripted path through the true world:
// wheel encoders (true wheel radii and tread differ from the nominal ones the
// odometry uses, plus per-step slip, slip growing with the yaw rate and
// occasional bumps (wheel_slip.hpp), so dead reckoning drifts as on a real
// robot), odometry integrated from those ticks, and a scanning LiDAR whose
// every beam is cast from where the sensor is at that beam's time (motion
// distortion), with range noise, dropouts, and the classes' partial returns;
// intensities (scale * reflectance / (1 + r / falloff), with noise) where the
// world gives its classes a reflectance.
//
// Time is kept in integer microseconds from 0; outputs carry start_utime +
// that. Randomness comes only from the seed, so a seed gives the same run.
#pragma once

#include <cstdint>
#include <deque>
#include <random>

#include "common/config/config_reader.hpp"
#include "common/robot/diff_drive.hpp"
#include "common/sensors/laser_scan.hpp"
#include "tools/sim/path_follower.hpp"
#include "tools/sim/wheel_slip.hpp"
#include "tools/sim/world.hpp"

namespace slamer {

struct SimOptions {
  double step = 0.005;                          // [s] integration step
  double encoder_period = 0.01;                 // [s] between encoder and odometry outputs
  int64_t start_utime = 1'700'000'000'000'000;  // utime of simulated time 0 (offline runs)
  double settle_time = 1.0;                     // [s] kept running after the path ends
  double max_duration = 3600.0;                 // [s] stop even if the path is not done
  bool motion_distortion = true;                // cast each beam from the pose at its own time
  double range_stddev = 0.01;                   // [m]
  double dropout_probability = 0.001;           // beams reported as NaN
  double wheel_radius_error_left = 0.0005;      // true radius = nominal * (1 + this)
  double wheel_radius_error_right = -0.0005;
  double tread_error = 0.005;   // true tread = nominal * (1 + this)
  double slip_stddev = 0.02;    // per-step relative noise on each wheel's travel
  WheelSlipOptions wheel_slip;  // slip growing with the yaw rate, bumps (all off by default)
};
void read_options(const ConfigReader& reader, SimOptions* options);

struct EncoderSample {
  int64_t utime = 0;
  int64_t seq = 0;
  int64_t left = 0;
  int64_t right = 0;
};

struct OdometrySample {
  int64_t utime = 0;
  int64_t seq = 0;
  Pose2 pose;
  double v = 0.0;
  double omega = 0.0;
};

struct GroundTruthSample {
  int64_t utime = 0;          // the scan's utime: the pose is the base's at that time
  int64_t publish_utime = 0;  // delivered with the scan
  Pose2 pose;                 // robot base in the map frame
};

class SimulatorSink {
 public:
  virtual ~SimulatorSink() = default;
  // `publish_utime` is when a real device would deliver the data (for logs).
  virtual void on_scan(const LaserScan& scan, int64_t publish_utime) = 0;
  virtual void on_encoders(const EncoderSample& sample) = 0;
  virtual void on_odometry(const OdometrySample& sample) = 0;
  virtual void on_ground_truth(const GroundTruthSample& sample) = 0;
};

class Simulator {
 public:
  Simulator(const TrueWorld& world, const WorldOptions& world_options, const RobotOptions& robot,
            const SimOptions& options, uint64_t seed);

  // Advances one step, reporting what became available; false once finished.
  bool step(SimulatorSink& sink);
  double time() const { return static_cast<double>(now_us_) * 1e-6; }
  const Pose2& true_pose() const { return pose_; }
  // Fraction of the path's steps completed, for progress display.
  double progress() const;

 private:
  Pose2 pose_at(int64_t time_us) const;  // from the recent history, interpolated
  LaserScan make_scan(int64_t start_us);

  const TrueWorld& world_;
  RobotOptions robot_;
  SimOptions options_;
  PathFollower follower_;
  std::size_t path_steps_;
  std::mt19937 lidar_rng_;
  std::mt19937 odometry_rng_;
  DiffDriveOdometry odometry_;
  WheelSlip wheel_slip_;

  int64_t step_us_;
  int64_t encoder_us_;
  int64_t scan_us_;
  int64_t now_us_ = 0;
  int64_t done_at_us_ = -1;
  Pose2 pose_;
  std::deque<std::pair<int64_t, Pose2>> history_;
  double left_ticks_ = 0.0;
  double right_ticks_ = 0.0;
  int64_t encoder_seq_ = 0;
  int64_t scan_seq_ = 0;
  int64_t next_scan_us_ = 0;
  IntensityModel intensity_model_;
};

}  // namespace slamer

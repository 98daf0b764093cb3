#include "tools/sim/simulator.hpp"

#include <cmath>
#include <limits>

namespace slamer {

void read_options(const ConfigReader& reader, SimOptions* o) {
  reader.read("step", &o->step, in_range(1e-4, 0.1));
  reader.read("encoder_period", &o->encoder_period, in_range(1e-4, 1.0));
  reader.read("start_utime", &o->start_utime, non_negative());
  reader.read("settle_time", &o->settle_time, non_negative());
  reader.read("max_duration", &o->max_duration, positive());
  reader.read("motion_distortion", &o->motion_distortion);
  reader.read("range_stddev", &o->range_stddev, non_negative());
  reader.read("dropout_probability", &o->dropout_probability, probability());
  reader.read("wheel_radius_error_left", &o->wheel_radius_error_left, in_range(-0.5, 0.5));
  reader.read("wheel_radius_error_right", &o->wheel_radius_error_right, in_range(-0.5, 0.5));
  reader.read("tread_error", &o->tread_error, in_range(-0.5, 0.5));
  reader.read("slip_stddev", &o->slip_stddev, in_range(0.0, 1.0));
  reader.read("turn_slip", &o->wheel_slip.turn_slip, in_range(-0.5, 0.5));
  reader.read("turn_slip_stddev", &o->wheel_slip.turn_slip_stddev, in_range(0.0, 0.5));
  reader.read("bump_rate", &o->wheel_slip.bump_rate, in_range(0.0, 100.0));
  reader.read("bump_travel", &o->wheel_slip.bump_travel, in_range(0.0, 1.0));
  reader.read("bump_duration", &o->wheel_slip.bump_duration, in_range(0.001, 10.0));
}

namespace {

int64_t to_us(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e6));
}

}  // namespace

Simulator::Simulator(const TrueWorld& world, const WorldOptions& world_options, const RobotOptions& robot,
                     const SimOptions& options, uint64_t seed)
    : world_(world),
      robot_(robot),
      options_(options),
      follower_(world_options.path, robot.base),
      path_steps_(world_options.path.size()),
      odometry_(robot.base),
      wheel_slip_(options.wheel_slip),
      step_us_(std::max<int64_t>(to_us(options.step), 1)),
      encoder_us_(std::max<int64_t>(to_us(options.encoder_period), 1)),
      scan_us_(std::max<int64_t>(to_us(robot.lidar.scan_period), 1)),
      pose_(world_options.start),
      intensity_model_(world_options.intensity) {
  // Independent streams, so changing one sensor's noise leaves the other's draws as they were.
  std::seed_seq lidar_seed{seed, uint64_t{1}};
  std::seed_seq odometry_seed{seed, uint64_t{2}};
  lidar_rng_.seed(lidar_seed);
  odometry_rng_.seed(odometry_seed);
  history_.emplace_back(0, pose_);
  odometry_.update(options_.start_utime, 0, 0);
}

double Simulator::progress() const {
  return path_steps_ == 0 ? 1.0 : static_cast<double>(follower_.current_step()) / static_cast<double>(path_steps_);
}

Pose2 Simulator::pose_at(int64_t time_us) const {
  if (time_us <= history_.front().first) {
    return history_.front().second;
  }
  for (std::size_t i = 1; i < history_.size(); ++i) {
    if (time_us <= history_[i].first) {
      const auto& [t0, p0] = history_[i - 1];
      const auto& [t1, p1] = history_[i];
      return interpolate(p0, p1, static_cast<double>(time_us - t0) / static_cast<double>(t1 - t0));
    }
  }
  return history_.back().second;
}

LaserScan Simulator::make_scan(int64_t start_us) {
  const LidarOptions& lidar = robot_.lidar;
  LaserScan scan;
  scan.utime = options_.start_utime + start_us;
  scan.sensor_utime = start_us;  // the device clock starts with the simulation
  scan.seq = scan_seq_++;
  scan.frame = lidar.frame;
  scan.angle_min = lidar.angle_min;
  scan.angle_increment = lidar.angle_increment();
  scan.range_min = static_cast<float>(lidar.range_min);
  scan.range_max = static_cast<float>(lidar.range_max);
  scan.time_increment = static_cast<float>(lidar.time_increment());
  scan.scan_period = static_cast<float>(lidar.scan_period);
  scan.ranges.resize(static_cast<std::size_t>(lidar.beams));
  std::normal_distribution<double> noise(0.0, options_.range_stddev);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Pose2 start_sensor = compose(pose_at(start_us), lidar.mount);
  const double time = static_cast<double>(start_us) * 1e-6;
  const bool intensities = world_.has_intensities();
  const IntensityModel& model = intensity_model_;
  std::normal_distribution<double> unit(0.0, 1.0);
  if (intensities) {
    scan.intensities.assign(scan.ranges.size(), 0.0f);
  }
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    float reflectance = 0.0f;
    const Pose2 sensor =
        options_.motion_distortion ? compose(pose_at(start_us + to_us(scan.beam_time(i))), lidar.mount) : start_sensor;
    const double distance = world_.cast({sensor.x, sensor.y}, sensor.theta + scan.angle(i), lidar.range_max + 1.0, time,
                                        lidar_rng_, intensities ? &reflectance : nullptr);
    const double measured = distance + (options_.range_stddev > 0.0 ? noise(lidar_rng_) : 0.0);
    const bool dropout = uniform(lidar_rng_) < options_.dropout_probability;
    float range = std::numeric_limits<float>::infinity();
    if (dropout) {
      range = std::numeric_limits<float>::quiet_NaN();
    } else if (std::isfinite(distance) && measured <= lidar.range_max) {
      range = measured < lidar.range_min ? -std::numeric_limits<float>::infinity() : static_cast<float>(measured);
    }
    scan.ranges[i] = range;
    if (intensities && std::isfinite(range)) {  // the URG reports 0 where nothing returned
      const double value = model.scale * reflectance / (1.0 + range / model.falloff) *
                           (1.0 + (model.noise > 0.0 ? model.noise * unit(lidar_rng_) : 0.0));
      scan.intensities[i] = static_cast<float>(std::max(0.0, value));
    }
  }
  return scan;
}

bool Simulator::step(SimulatorSink& sink) {
  if (done_at_us_ >= 0 && now_us_ >= done_at_us_ + to_us(options_.settle_time)) {
    return false;
  }
  if (now_us_ >= to_us(options_.max_duration)) {
    return false;
  }
  const double dt = static_cast<double>(step_us_) * 1e-6;
  const VelocityCommand command = follower_.update(pose_, dt);
  if (follower_.done() && done_at_us_ < 0) {
    done_at_us_ = now_us_;
  }

  // The base moves as commanded; the wheels turn by what that takes on the
  // true (not nominal) geometry, with slip.
  const DiffDriveOptions& base = robot_.base;
  const double true_tread = base.tread * (1.0 + options_.tread_error);
  double left_travel = (command.v - command.omega * true_tread / 2.0) * dt;
  double right_travel = (command.v + command.omega * true_tread / 2.0) * dt;
  std::normal_distribution<double> slip(0.0, options_.slip_stddev);
  const double left_slip = options_.slip_stddev > 0.0 ? slip(odometry_rng_) : 0.0;
  const double right_slip = options_.slip_stddev > 0.0 ? slip(odometry_rng_) : 0.0;
  left_travel *= 1.0 + left_slip;
  right_travel *= 1.0 + right_slip;
  wheel_slip_.apply(dt, command.omega, &left_travel, &right_travel, odometry_rng_);
  left_ticks_ += travel_ticks(left_travel, base.wheel_radius_left * (1.0 + options_.wheel_radius_error_left), base);
  right_ticks_ += travel_ticks(right_travel, base.wheel_radius_right * (1.0 + options_.wheel_radius_error_right), base);
  pose_ = compose(pose_, exp_se2({command.v * dt, 0.0, command.omega * dt}));
  now_us_ += step_us_;
  history_.emplace_back(now_us_, pose_);
  while (history_.size() > 2 && history_[1].first < now_us_ - 4 * scan_us_) {
    history_.pop_front();
  }

  // A scan is delivered once its last beam has been measured, i.e. during the
  // step just taken: before this step's encoder sample, so outputs stay in time order.
  const int64_t scan_length_us = to_us(robot_.lidar.time_increment() * (robot_.lidar.beams - 1));
  while (next_scan_us_ + scan_length_us <= now_us_) {
    const int64_t publish_utime = options_.start_utime + next_scan_us_ + scan_length_us;
    sink.on_ground_truth({options_.start_utime + next_scan_us_, publish_utime, pose_at(next_scan_us_)});
    sink.on_scan(make_scan(next_scan_us_), publish_utime);
    next_scan_us_ += scan_us_;
  }
  if (now_us_ % encoder_us_ == 0) {
    const int64_t utime = options_.start_utime + now_us_;
    const EncoderSample encoders{utime, encoder_seq_, std::llround(left_ticks_), std::llround(right_ticks_)};
    sink.on_encoders(encoders);
    odometry_.update(utime, encoders.left, encoders.right);
    sink.on_odometry({utime, encoder_seq_, odometry_.pose(), odometry_.speed(), odometry_.yaw_rate()});
    ++encoder_seq_;
  }
  return true;
}

}  // namespace slamer

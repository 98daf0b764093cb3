// Sample -> odometry_t + wheel_encoders_t (see lcmtypes/wheel_encoders_t.lcm for the signs).
#include "drivers/wheels/backends.hpp"
#include "drivers/wheels/wheels_report.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace slamer {

void publish_sample(Bus& bus, const WheelsConfig& config, const tfrog::Kinematics& kinematics,
                    const tfrog::OdometrySample& sample, const char* source, int64_t* seq) {
  odometry_t odometry{};
  odometry.utime = sample.utime;
  odometry.seq = *seq;
  odometry.x = sample.pose.x;
  odometry.y = sample.pose.y;
  odometry.theta = sample.pose.theta;
  odometry.v = sample.v;
  odometry.omega = sample.omega;
  bus.publish(config.channels.odometry, odometry);
  wheel_encoders_t encoders{};
  encoders.utime = sample.utime;
  encoders.seq = *seq;
  encoders.source = source;
  encoders.nwheels = 2;
  const auto ticks = forward_ticks(sample.ticks, kinematics);
  encoders.ticks.assign(ticks.begin(), ticks.end());
  bus.publish(config.channels.wheel_encoders, encoders);
  ++*seq;
}

}  // namespace slamer

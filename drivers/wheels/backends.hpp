// The two device loops of slamer-wheels on the Bus (common/process/bus.hpp): each opens its
// device, feeds bytes/frames to the pure library, publishes ODOMETRY and
// WHEEL_ENCODERS per frame, updates PROCESS_STATUS, and reopens after a loss.
#pragma once

#include "common/process/bus.hpp"
#include "drivers/wheels/tfrog_session.hpp"
#include "drivers/wheels/wheels_options.hpp"

namespace slamer {

// Wire the backend onto the bus (the caller then runs it).
void start_tfrog(Bus& bus, const WheelsConfig& config);
void start_can(Bus& bus, const WheelsConfig& config);
// Publishes one sample as odometry_t and wheel_encoders_t.
void publish_sample(Bus& bus, const WheelsConfig& config, const tfrog::Kinematics& kinematics,
                    const tfrog::OdometrySample& sample, const char* source, int64_t* seq);

}  // namespace slamer

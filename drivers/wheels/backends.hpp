// The two device loops of slamer-wheels on the process skeleton: each opens its
// device, feeds bytes/frames to the pure library, publishes ODOMETRY and
// WHEEL_ENCODERS per frame, updates PROCESS_STATUS, and reopens after a loss.
#pragma once

#include "common/process/lcm_process.hpp"
#include "drivers/wheels/tfrog_session.hpp"
#include "drivers/wheels/wheels_options.hpp"

namespace slamer {

int run_tfrog(LcmProcess& process, const WheelsConfig& config);
int run_can(LcmProcess& process, const WheelsConfig& config);
// Publishes one sample as odometry_t and wheel_encoders_t.
void publish_sample(LcmProcess& process, const WheelsConfig& config, const tfrog::Kinematics& kinematics,
                    const tfrog::OdometrySample& sample, const char* source, int64_t* seq);

}  // namespace slamer

// What slamer-localizer's results look like on the bus: POSE, PARTICLES and
// the PROCESS_STATUS state, from the filter's and the node's types.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "localizer/localizer_config.hpp"
#include "localizer/localizer_node.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/pose_estimate_t.hpp"

namespace slamer {

int8_t to_status(LocalizerStatus status);
pose_estimate_t to_pose_message(const UpdateResult& result, int64_t utime, int particles);
// At most `count` particles, evenly picked, with linear weights.
particles_t to_particles_message(const std::vector<Particle>& particles, int64_t utime, int count);

// PROCESS_STATUS's state and message: the filter's status and the inputs it goes without.
std::pair<int8_t, std::string> process_state(LocalizerStatus status, const std::string& reason,
                                             const InputHealth& health, const LocalizerChannels& channels);

// An INITIAL_POSE for a log line: "(x, y, theta), sigma (sx, sy, stheta)".
std::string describe(const initial_pose_t& message);

}  // namespace slamer

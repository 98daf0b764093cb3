// The config file of slamer-sim (config/sim.yaml): process, simulation noise
// and rates, and the channel names it publishes on.
#pragma once

#include "common/process/process_options.hpp"
#include "tools/sim/simulator.hpp"

namespace slamer {

struct SimChannels {
  std::string lidar = "LIDAR";
  std::string wheel_encoders = "WHEEL_ENCODERS";
  std::string odometry = "ODOMETRY";
  std::string ground_truth = "GROUND_TRUTH";
};

struct SimProcessConfig {
  ProcessOptions process;
  SimOptions sim;
  SimChannels channels;
};
void read_options(const ConfigReader& reader, SimProcessConfig* config);

}  // namespace slamer

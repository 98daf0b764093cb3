#include "tools/sim/sim_config.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, SimProcessConfig* config) {
  read_options(reader.section("process"), &config->process);
  read_options(reader.section("sim"), &config->sim);
  const ConfigReader channels = reader.section("channels");
  channels.read("lidar", &config->channels.lidar);
  channels.read("wheel_encoders", &config->channels.wheel_encoders);
  channels.read("odometry", &config->channels.odometry);
  channels.read("ground_truth", &config->channels.ground_truth);
}

}  // namespace slamer

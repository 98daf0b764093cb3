#include "localizer/localizer_config.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, LocalizerProcessConfig* config) {
  read_options(reader.section("process"), &config->process);
  read_options(reader.section("localizer"), &config->localizer);
  const ConfigReader channels = reader.section("channels");
  channels.read("lidar", &config->channels.lidar);
  channels.read("odometry", &config->channels.odometry);
  channels.read("line_objects", &config->channels.line_objects);
  channels.read("initial_pose", &config->channels.initial_pose);
  channels.read("pose", &config->channels.pose);
  channels.read("semantic_objects", &config->channels.semantic_objects);
  channels.read("particles", &config->channels.particles);
  reader.read("map", &config->map);
  reader.read("robot", &config->robot);
  config->map = reader.resolve_path(config->map);
  config->robot = reader.resolve_path(config->robot);
  reader.read("particles_out", &config->particles_out, in_range(0, 100000));
  reader.read("particles_period", &config->particles_period, positive());
  reader.read("pose_file", &config->pose_file);
  config->pose_file = reader.resolve_path(config->pose_file);
  reader.read("pose_save_period", &config->pose_save_period, in_range(0.1, 3600.0));
}

}  // namespace slamer

#include "recognizer/recognizer_config.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, RecognizerProcessConfig* config) {
  read_options(reader.section("process"), &config->process);
  read_options(reader.section("recognizer"), &config->recognizer);
  const ConfigReader channels = reader.section("channels");
  channels.read("lidar", &config->lidar_channel);
  channels.read("line_objects", &config->line_objects_channel);
  const ConfigReader inputs = reader.section("inputs");
  inputs.read("max_beams", &config->max_beams, in_range(1, 10'000'000));
  inputs.read("scan_timeout", &config->scan_timeout, in_range(0.01, 60.0));
}

}  // namespace slamer

#include "tools/eval/eval_config.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, EvalConfig* config) {
  read_options(reader.section("eval"), &config->eval);
  const ConfigReader channels = reader.section("channels");
  channels.read("ground_truth", &config->channels.ground_truth);
  channels.read("pose", &config->channels.pose);
  channels.read("odometry", &config->channels.odometry);
  channels.read("line_objects", &config->channels.line_objects);
  channels.read("semantic_objects", &config->channels.semantic_objects);
}

}  // namespace slamer

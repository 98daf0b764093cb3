// The config file of slamer-eval (config/eval.yaml).
#pragma once

#include "tools/eval/evaluation.hpp"

namespace slamer {

struct EvalChannels {
  std::string ground_truth = "GROUND_TRUTH";
  std::string pose = "POSE";
  std::string odometry = "ODOMETRY";
  std::string line_objects = "LINE_OBJECTS";
  std::string semantic_objects = "SEMANTIC_OBJECTS";
};

struct EvalConfig {
  EvalOptions eval;
  EvalChannels channels;
};
void read_options(const ConfigReader& reader, EvalConfig* config);

}  // namespace slamer

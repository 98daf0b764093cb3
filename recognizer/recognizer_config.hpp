// The config file of slamer-recognizer (config/recognizer.yaml).
#pragma once

#include "common/process/process_options.hpp"
#include "recognizer/recognizer_options.hpp"

namespace slamer {

struct RecognizerProcessConfig {
  ProcessOptions process;
  RecognizerOptions recognizer;
  std::string lidar_channel = "LIDAR";
  std::string line_objects_channel = "LINE_OBJECTS";
  // inputs:
  int max_beams = 100000;     // larger scans are rejected as malformed
  double scan_timeout = 2.0;  // [s] no scan for this long: PROCESS_STATUS degraded
};
void read_options(const ConfigReader& reader, RecognizerProcessConfig* config);

}  // namespace slamer

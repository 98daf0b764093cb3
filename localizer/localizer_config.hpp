// The config file of slamer-localizer (config/localizer.yaml).
#pragma once

#include "common/process/process_options.hpp"
#include "localizer/localizer_options.hpp"

namespace slamer {

struct LocalizerChannels {
  std::string lidar = "LIDAR";
  std::string odometry = "ODOMETRY";
  std::string line_objects = "LINE_OBJECTS";
  std::string initial_pose = "INITIAL_POSE";
  std::string pose = "POSE";
  std::string semantic_objects = "SEMANTIC_OBJECTS";
  std::string particles = "PARTICLES";
};

struct LocalizerProcessConfig {
  ProcessOptions process;
  LocalizerOptions localizer;
  LocalizerChannels channels;
  std::string map;                // semantic map YAML, resolved against the config file
  std::string robot;              // robot YAML (for the LiDAR mount), resolved against the config file
  int particles_out = 200;        // particles sent on PARTICLES (evenly picked)
  double particles_period = 0.2;  // [s] at most one PARTICLES per period
  // Live: the last good pose is written here (atomically) every pose_save_period and at a
  // clean stop, and a restart resumes from it. Empty: not kept.
  std::string pose_file;
  double pose_save_period = 1.0;  // [s]
  // Start with global localization (the robot anywhere on the map), as an
  // INITIAL_POSE with cov[0] < 0 would; a resumed pose is then not used.
  // From the command line only (--global), not the YAML.
  bool start_global = false;
};
void read_options(const ConfigReader& reader, LocalizerProcessConfig* config);

}  // namespace slamer

// Options of slamer-urg (config/urg.yaml), nested by concern, with the defaults.
#pragma once

#include <string>

#include "common/config/config_reader.hpp"
#include "common/process/process_options.hpp"
#include "drivers/urg/urg_session.hpp"

namespace slamer::urg {

struct UrgConnectionOptions {
  std::string host = "192.168.0.10";  // the URM-40LC-EW's factory address
  int port = 10940;
  std::string device;  // a serial/USB device (e.g. /dev/ttyACM0): used instead of TCP when set
  double connect_timeout_s = 2.0;
  double max_backoff_s = 1.0;  // retry delays double from 0.1 s up to this
};

struct UrgProcessConfig {
  ProcessOptions process;
  std::string lidar_channel = "LIDAR";
  UrgConnectionOptions connection;
  UrgSessionOptions session;  // scan (steps, cluster, intensities, frame), time_sync, faults
};
void read_options(const ConfigReader& reader, UrgProcessConfig* config);

}  // namespace slamer::urg

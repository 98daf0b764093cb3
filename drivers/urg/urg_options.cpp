#include "drivers/urg/urg_options.hpp"

namespace slamer::urg {

void read_options(const ConfigReader& reader, UrgProcessConfig* config) {
  read_options(reader.section("process"), &config->process);
  reader.section("channels").read("lidar", &config->lidar_channel);
  const ConfigReader connection = reader.section("connection");
  UrgConnectionOptions& c = config->connection;
  connection.read("host", &c.host);
  connection.read("port", &c.port, in_range(1, 65535));
  connection.read("device", &c.device);
  connection.read("connect_timeout", &c.connect_timeout_s, positive());
  connection.read("max_backoff", &c.max_backoff_s, in_range(0.1, 60));
  UrgSessionOptions& s = config->session;
  connection.read("reply_timeout", &s.reply_timeout_s, positive());
  connection.read("silence_periods", &s.silence_periods, in_range(1, 100));
  connection.read("resets_before_reboot", &s.resets_before_reboot, in_range(0, 100));
  const ConfigReader scan = reader.section("scan");
  scan.read("first_step", &s.first_step, at_least(-1));
  scan.read("last_step", &s.last_step, at_least(-1));
  scan.read("cluster", &s.cluster, in_range(1, 99));
  scan.read("intensities", &s.intensities);
  scan.read("frame", &s.frame);
  if (s.first_step >= 0 && s.last_step >= 0 && s.last_step < s.first_step) {
    scan.fail("last_step", "must be >= scan.first_step (or -1 for the sensor's AMAX)");
  }
  const ConfigReader sync = reader.section("time_sync");
  sync.read("burst", &s.sync_samples, in_range(0, 1000));
  sync.read("tm1_while_streaming_hz", &s.tm1_while_streaming_hz, in_range(0, 100));
}

}  // namespace slamer::urg

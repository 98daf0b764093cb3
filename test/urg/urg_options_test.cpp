// config/urg.yaml's loader: defaults, overrides, and one-line errors naming the key.
#include <gtest/gtest.h>

#include "drivers/urg/urg_options.hpp"

namespace slamer::urg {
namespace {

TEST(UrgOptions, DefaultsAndKeys) {
  const auto config = parse_options<UrgProcessConfig>(
      "connection: {host: 127.0.0.1, port: 2000}\nscan: {first_step: 10, last_step: 20, cluster: 2, intensities: "
      "true}\n"
      "time_sync: {burst: 0, tm1_while_streaming_hz: 0}\nchannels: {lidar: SCAN}\n",
      "test");
  EXPECT_EQ(config.connection.host, "127.0.0.1");
  EXPECT_EQ(config.connection.port, 2000);
  EXPECT_EQ(config.session.first_step, 10);
  EXPECT_EQ(config.session.cluster, 2);
  EXPECT_TRUE(config.session.intensities);
  EXPECT_EQ(config.session.sync_samples, 0);
  EXPECT_EQ(config.lidar_channel, "SCAN");
  const UrgProcessConfig defaults;
  EXPECT_EQ(defaults.connection.host, "192.168.0.10");
  EXPECT_DOUBLE_EQ(defaults.connection.connect_timeout_s, 2.0);
  EXPECT_DOUBLE_EQ(defaults.connection.max_backoff_s, 1.0);
}

TEST(UrgOptions, BadValuesNameTheirKey) {
  auto message = [](const std::string& yaml) {
    try {
      parse_options<UrgProcessConfig>(yaml, "test");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("connection: {port: 70000}").find("connection.port"), std::string::npos);
  EXPECT_NE(message("scan: {clusterr: 2}").find("scan.clusterr"), std::string::npos);
  EXPECT_NE(message("scan: {first_step: 30, last_step: 20}").find("scan.last_step"), std::string::npos);
  EXPECT_NE(message("scan: {cluster: 0}").find("scan.cluster"), std::string::npos);
}

}  // namespace
}  // namespace slamer::urg

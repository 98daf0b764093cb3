#include "common/process/process_health.hpp"

#include <gtest/gtest.h>

#include "slamer/channel_stats_t.hpp"

namespace slamer {
namespace {

TEST(ProcessHealth, CountsPerChannelAndTotals) {
  ProcessHealth health("slamer-test", 1234, 1'000'000);
  health.add_channel("LIDAR", channel_stats_t::SUBSCRIBED);
  health.add_channel("LINE_OBJECTS", channel_stats_t::PUBLISHED);
  for (int i = 0; i < 5; ++i) {
    health.count_message("LIDAR", channel_stats_t::SUBSCRIBED, 2'000'000 + i);
  }
  health.count_message("LINE_OBJECTS", channel_stats_t::PUBLISHED, 2'000'010);
  health.count_decode_error("LIDAR", DecodeStatus::kWrongFingerprint, 2'000'020);
  health.count_decode_error("ODOMETRY", DecodeStatus::kMalformed, 2'000'030);
  health.count_drop("LIDAR", channel_stats_t::SUBSCRIBED, 2);
  health.record_processing_time(0.001);
  health.record_processing_time(0.003);

  const process_status_t status = health.status(4'500'000);
  EXPECT_EQ(status.process, "slamer-test");
  EXPECT_EQ(status.pid, 1234);
  EXPECT_EQ(status.utime, 4'500'000);
  EXPECT_DOUBLE_EQ(status.uptime, 3.5);
  EXPECT_EQ(status.state, process_status_t::OK);
  EXPECT_EQ(status.messages_in, 5);
  EXPECT_EQ(status.messages_out, 1);
  EXPECT_EQ(status.decode_errors, 2);
  EXPECT_EQ(status.drops, 2);
  EXPECT_DOUBLE_EQ(status.processing_time_p50, 0.001);
  EXPECT_DOUBLE_EQ(status.processing_time_p99, 0.003);
  ASSERT_EQ(status.nchannels, 3);
  ASSERT_EQ(status.channels.size(), 3u);
  // Sorted by channel name: LIDAR, LINE_OBJECTS, ODOMETRY.
  EXPECT_EQ(status.channels[0].channel, "LIDAR");
  EXPECT_EQ(status.channels[0].messages, 5);
  EXPECT_EQ(status.channels[0].decode_errors, 1);
  EXPECT_EQ(status.channels[0].drops, 2);
  EXPECT_EQ(status.channels[1].direction, channel_stats_t::PUBLISHED);
  EXPECT_EQ(status.channels[2].channel, "ODOMETRY");
  EXPECT_EQ(status.channels[2].decode_errors, 1);
}

TEST(ProcessHealth, ErrorSummaryIsOneLineAndResets) {
  ProcessHealth health("p", 1, 0);
  EXPECT_EQ(health.take_error_summary(), "");
  for (int i = 0; i < 3; ++i) {
    health.count_decode_error("LIDAR", DecodeStatus::kWrongFingerprint, i);
  }
  health.count_decode_error("ODOMETRY", DecodeStatus::kMalformed, 9);
  health.count_handler_error("LIDAR: bad scan");
  EXPECT_EQ(health.take_error_summary(),
            "4 decode errors: LIDAR 3 (wrong fingerprint), ODOMETRY 1 (truncated or malformed); "
            "1 handler error, last: LIDAR: bad scan");
  EXPECT_EQ(health.take_error_summary(), "");
  EXPECT_EQ(health.status(10).decode_errors, 4);  // totals are kept
}

TEST(ProcessHealth, StateAndMessage) {
  ProcessHealth health("p", 1, 0);
  health.set_state(process_status_t::DEGRADED, "no ODOMETRY for 2.0 s");
  const process_status_t status = health.status(0);
  EXPECT_EQ(status.state, process_status_t::DEGRADED);
  EXPECT_EQ(status.message, "no ODOMETRY for 2.0 s");
}

TEST(ProcessHealth, AnEventIsInTheNextPublishedStatusOnly) {
  ProcessHealth health("p", 1, 0);
  health.note_event(process_status_t::DEGRADED, "LIDAR's driver restarted");
  EXPECT_EQ(health.status(1).state, process_status_t::OK);  // the state now
  process_status_t s = health.take_status(1);
  EXPECT_EQ(s.state, process_status_t::DEGRADED);
  EXPECT_EQ(s.message, "LIDAR's driver restarted (now OK)");
  s = health.take_status(2);  // said once
  EXPECT_EQ(s.state, process_status_t::OK);
  EXPECT_EQ(s.message, "");
  // Worse than the event: the state wins; more events than kept: counted.
  health.set_state(process_status_t::ERROR, "lost");
  for (int i = 0; i < 5; ++i) {
    health.note_event(process_status_t::DEGRADED, "restart " + std::to_string(i));
  }
  s = health.take_status(3);
  EXPECT_EQ(s.state, process_status_t::ERROR);
  EXPECT_EQ(s.message, "restart 0; restart 1; restart 2; 2 more (now lost)");
  s = health.take_status(4);
  EXPECT_EQ(s.message, "lost");
}

}  // namespace
}  // namespace slamer

#include "tools/render/frame_collector.hpp"

#include <gtest/gtest.h>

#include "common/process/convert.hpp"
#include "slamer/particles_t.hpp"

namespace slamer {
namespace {

template <class Message>
std::vector<uint8_t> encoded(const Message& m) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

std::vector<uint8_t> scan_at(int64_t utime) {
  LaserScan scan;
  scan.utime = utime;
  scan.angle_increment = 0.01;
  scan.ranges.assign(10, 2.0f);
  return encoded(to_message(scan));
}

std::vector<uint8_t> pose(int64_t utime, double x) {
  return encoded(make_exact_pose(utime, {x, 0.0, 0.0}));
}

// Each kept scan becomes a frame when the next scan comes, with what was
// published for its utime meanwhile; damaged messages are skipped.
TEST(FrameCollector, AScanIsAFrameWithItsPosesOnceTheNextScanComes) {
  FrameCollector collector(2);
  EXPECT_TRUE(collector.add("LIDAR", scan_at(1'000'000)).empty());
  EXPECT_TRUE(collector.add("POSE", pose(1'000'000, 1.5)).empty());
  EXPECT_TRUE(collector.add("GROUND_TRUTH", pose(1'000'000, 1.4)).empty());
  std::vector<uint8_t> damaged = pose(1'000'000, 9.0);
  damaged.resize(damaged.size() - 3);
  EXPECT_TRUE(collector.add("POSE", damaged).empty());
  particles_t particles{};
  particles.utime = 1'000'000;
  particles.n = 2;
  particles.x = {1.0, 2.0};
  particles.y = {0.0, 0.0};
  particles.theta = {0.0, 0.0};
  particles.weight = {0.5, 0.5};
  EXPECT_TRUE(collector.add("PARTICLES", encoded(particles)).empty());
  std::vector<uint8_t> bad_scan = scan_at(1'500'000);
  bad_scan.resize(10);
  EXPECT_TRUE(collector.add("LIDAR", bad_scan).empty());  // neither a frame nor counted

  const std::vector<Frame> first = collector.add("LIDAR", scan_at(1'025'000));
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].utime, 1'000'000);
  EXPECT_DOUBLE_EQ(first[0].elapsed, 0.0);
  ASSERT_TRUE(first[0].estimate && first[0].truth && first[0].scan);
  EXPECT_DOUBLE_EQ(first[0].estimate->x, 1.5);
  EXPECT_DOUBLE_EQ(first[0].truth->x, 1.4);
  EXPECT_EQ(first[0].scan->ranges.size(), 10u);
  ASSERT_EQ(first[0].particles.size(), 2u);
  EXPECT_DOUBLE_EQ(first[0].particles[1].x, 2.0);

  // The second scan is skipped (every 2nd); the third waits for the end of the log.
  EXPECT_TRUE(collector.add("POSE", pose(1'025'000, 2.0)).empty());
  EXPECT_TRUE(collector.add("LIDAR", scan_at(1'050'000)).empty());
  const std::vector<Frame> last = collector.finish();
  ASSERT_EQ(last.size(), 1u);
  EXPECT_EQ(last[0].utime, 1'050'000);
  EXPECT_NEAR(last[0].elapsed, 0.05, 1e-12);
  EXPECT_FALSE(last[0].estimate);  // the skipped scan's pose is not this one's
  EXPECT_TRUE(collector.finish().empty());
}

}  // namespace
}  // namespace slamer

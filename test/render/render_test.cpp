#include <gtest/gtest.h>

#include "tools/render/renderer.hpp"

namespace slamer {
namespace {

SemanticMap empty_map() {
  SemanticMap map;
  map.geometry = {100, 50, 0.1, {}};
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  map.occupancy[map.geometry.index(99, 49)] = Occupancy::kOccupied;
  return map;
}

cv::Vec3b pixel(const cv::Mat& image, int x, int y) {
  return image.at<cv::Vec3b>(y, x);
}

TEST(FrameRenderer, DrawsPosesScanAndObjectsWhereTheyAre) {
  const SemanticMap map = empty_map();
  RenderOptions options;
  options.pixels_per_cell = 2.0;
  const FrameRenderer renderer(map, options);
  Frame frame;
  frame.truth = Pose2{2.0, 2.5, 0.0};
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = 0.1;
  scan.ranges = {3.0f, std::numeric_limits<float>::quiet_NaN()};
  frame.scan = scan;
  LineObjectSet objects;
  objects.class_names = {"open_door", "no_entry_line"};
  objects.objects.push_back({LineKind::kSpatial, {6.0, 1.0}, {6.0, 4.0}, 0, {0.1f, 0.9f}, 1});
  frame.semantic = objects;
  const cv::Mat image = renderer.draw(frame);
  ASSERT_EQ(image.cols, 200);
  ASSERT_EQ(image.rows, 100);
  // Occupied cell (99, 49) is the top-right 2x2 pixels, dark.
  EXPECT_EQ(pixel(image, 199, 0), cv::Vec3b(60, 60, 60));
  // The no-entry line at x = 6 m (pixel 120) is red (BGR 0, 0, 255).
  EXPECT_EQ(pixel(image, 120, 50), cv::Vec3b(0, 0, 255));
  // The scan point 3 m ahead of the robot at (5.0, 2.5) -> pixel (100, 49/50) is red-ish.
  const cv::Vec3b hit = pixel(image, 100, 50);
  EXPECT_GT(hit[2], 200);
  EXPECT_LT(hit[1], 50);
  // The truth pose's heading line is green, 0.3 m ahead of it.
  const cv::Vec3b heading = pixel(image, 46, 49);  // row 100 - 1 - 50
  EXPECT_GT(heading[1], 120);
  EXPECT_LT(heading[0], 80);
  // Far from everything the map stays white.
  EXPECT_EQ(pixel(image, 170, 80), cv::Vec3b(255, 255, 255));
}

}  // namespace
}  // namespace slamer

// The dataset readers on the excerpts in test/datasets/excerpts/ (synthetic
// lines in each format, malformed ones included) and on single lines.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "tools/datasets/dataset_import.hpp"
#include "tools/datasets/dataset_records.hpp"

namespace slamer {
namespace {

std::string excerpt(const std::string& name) {
  return std::string(SLAMER_SOURCE_DIR "/test/datasets/excerpts/") + name;
}

TEST(DatasetRecords, RobotLaserLine) {
  DatasetRecord r;
  std::string error;
  const std::string line =
      "ROBOTLASER1 0 -1.5 3.0 0.75 30.0 0.01 0 5 1.0 2.0 30.0 3.0 0.5 2 7 8 1.2 0.1 0.2 1.0 0.0 0.2 0.1 0 0.5 0.3 "
      "1.0 42.5 host 42.6";
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kCarmen, line, &r, &error)) << error;
  EXPECT_EQ(r.kind, RecordKind::kScan);
  EXPECT_EQ(r.tag, "ROBOTLASER1");
  ASSERT_EQ(r.scan.ranges.size(), 5u);
  EXPECT_DOUBLE_EQ(r.scan.angle_min, -1.5);
  EXPECT_DOUBLE_EQ(r.scan.angle_increment, 0.75);
  EXPECT_FLOAT_EQ(r.scan.range_max, 30.0f);
  EXPECT_TRUE(std::isinf(r.scan.ranges[2]));  // at max_range: no return
  EXPECT_FLOAT_EQ(r.scan.ranges[4], 0.5f);
  EXPECT_DOUBLE_EQ(r.pose.x, 1.2);
  EXPECT_DOUBLE_EQ(r.base_pose.theta, 0.2);
  EXPECT_EQ(r.scan.utime, 42'500'000);
  // Truncated inside the remissions, a NaN pose, a count past the line.
  EXPECT_FALSE(parse_dataset_record(DatasetFormat::kCarmen, line.substr(0, 60), &r, &error));
  EXPECT_NE(error.find("ROBOTLASER1"), std::string::npos);
  std::string nan_pose = line;
  nan_pose.replace(nan_pose.find("1.2 0.1"), 3, "nan");
  EXPECT_FALSE(parse_dataset_record(DatasetFormat::kCarmen, nan_pose, &r, &error));
  EXPECT_FALSE(
      parse_dataset_record(DatasetFormat::kCarmen, "ROBOTLASER1 0 -1.5 3.0 0.75 30 0.01 0 9999999", &r, &error));
}

TEST(DatasetRecords, OdometryLinesAndOthers) {
  DatasetRecord r;
  std::string error;
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kCarmen, "ODOM 1.5 -2 4.0 0.3 0.1 0 12.25 h 12.3", &r, &error));
  EXPECT_EQ(r.kind, RecordKind::kOdometry);
  EXPECT_DOUBLE_EQ(r.pose.x, 1.5);
  EXPECT_NEAR(r.pose.theta, 4.0 - 2 * std::numbers::pi, 1e-12);  // wrapped into (-pi, pi]
  EXPECT_DOUBLE_EQ(r.v, 0.3);
  EXPECT_EQ(r.scan.utime, 12'250'000);
  // fr079 stamps a re-anchoring ODOM with -0.96 s: the pose counts, the time is marked unusable.
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kCarmen, "ODOM 1 2 3 0 0 0 -0.958593 h -0.95", &r, &error));
  EXPECT_EQ(r.scan.utime, -1);
  EXPECT_FALSE(parse_dataset_record(DatasetFormat::kCarmen, "ODOM 1 2", &r, &error));
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kCarmen, "PARAM a b", &r, &error));
  EXPECT_EQ(r.kind, RecordKind::kIgnored);
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kCmu, "O -94.2 -139.9 -1.34 0.5", &r, &error));
  EXPECT_EQ(r.kind, RecordKind::kOdometry);
  EXPECT_DOUBLE_EQ(r.pose.x, -0.942);  // cm to m
  EXPECT_FALSE(parse_dataset_record(DatasetFormat::kCmu, "O 1 2 x 0.5", &r, &error));
  ASSERT_TRUE(parse_dataset_record(DatasetFormat::kMines, "", &r, &error));
  EXPECT_EQ(r.kind, RecordKind::kIgnored);
}

TEST(DatasetImport, CorrectedCarmenExcerpt) {
  const ImportedLog log = import_dataset(excerpt("carmen_corrected.log"), {});
  EXPECT_TRUE(log.corrected);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.malformed, 2);
  ASSERT_EQ(log.errors.size(), 2u);
  EXPECT_NE(log.errors[0].find("carmen_corrected.log:8: FLASER"), std::string::npos) << log.errors[0];
  EXPECT_NE(log.errors[1].find("carmen_corrected.log:13: ODOM"), std::string::npos) << log.errors[1];
  EXPECT_TRUE(std::isinf(log.scans[0].ranges[2]));  // 50 m (aces) and 81.91 m (fr079) are no return
  EXPECT_TRUE(std::isinf(log.scans[0].ranges[3]));
  EXPECT_EQ(log.scans[1].sensor_utime, 10'500'000);
  ASSERT_EQ(log.reference.size(), 2u);
  EXPECT_DOUBLE_EQ(log.reference[1].x, 1.4);
  // Raw odometry: from the last ODOM before the first scan, then inv(anchor) (+) last ODOM before scan 2.
  ASSERT_EQ(log.scan_odometry.size(), 2u);
  EXPECT_NEAR(log.scan_odometry[0].x, 0.1, 1e-12);
  const Pose2 step = between(log.scan_odometry[0], log.scan_odometry[1]);
  EXPECT_NEAR(step.x, 0.5 * std::cos(0.5), 1e-9);
  EXPECT_NEAR(step.y, -0.5 * std::sin(0.5), 1e-9);
  EXPECT_NEAR(step.theta, 0.1, 1e-9);
  // The stream: raw_0 at scan 0's utime, the ODOM in between, raw_1 at scan 1's utime.
  ASSERT_EQ(log.odometry.size(), 3u);
  EXPECT_EQ(log.odometry[0].utime, log.scans[0].utime);
  EXPECT_EQ(log.odometry[2].utime, log.scans[1].utime);
  EXPECT_GT(log.odometry[1].utime, log.odometry[0].utime);
  EXPECT_LT(log.odometry[1].utime, log.odometry[2].utime);
  EXPECT_NEAR(between(log.odometry[0].pose, log.odometry[1].pose).x, 0.2 * std::cos(0.5), 1e-9);  // 0.2 m along x
  const auto order = merge_streams(log);
  ASSERT_EQ(order.size(), 7u);
  EXPECT_EQ(order[0].kind, StreamKind::kOdometry);
  EXPECT_EQ(order[1].kind, StreamKind::kScan);
  EXPECT_EQ(order[2].kind, StreamKind::kGroundTruth);
}

TEST(DatasetImport, RobotLaserExcerptCarriesTheLaserOffset) {
  ImportOptions options;
  options.corrected = ImportOptions::Corrected::kNo;
  const ImportedLog log = import_dataset(excerpt("robotlaser1.log"), options);
  EXPECT_FALSE(log.corrected);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.malformed, 1);  // the negative range
  EXPECT_TRUE(log.reference.empty());
  ASSERT_TRUE(log.laser_mount.has_value());
  EXPECT_NEAR(log.laser_mount->x, 0.2, 1e-9);
  EXPECT_NEAR(log.laser_mount->y, 0.0, 1e-9);
  EXPECT_TRUE(std::isinf(log.scans[0].ranges[2]));
  EXPECT_TRUE(std::isinf(log.scans[1].ranges[2]));  // within 1 mm of max_range
  EXPECT_FLOAT_EQ(log.scans[1].ranges[4], 4.0f);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_GT(log.odometry[0].utime, log.scans[1].utime);
}

TEST(DatasetImport, WeanExcerpt) {
  ImportOptions options;
  options.format = DatasetFormat::kCmu;
  const ImportedLog log = import_dataset(excerpt("wean.log"), options);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.malformed, 2);
  EXPECT_NE(log.errors[0].find("wean.log:4: O"), std::string::npos) << log.errors[0];
  EXPECT_NE(log.errors[1].find("wean.log:6: L"), std::string::npos) << log.errors[1];
  EXPECT_TRUE(std::isinf(log.scans[0].ranges[0]));    // 8183 cm
  EXPECT_TRUE(std::isinf(log.scans[0].ranges[179]));  // 8191 cm
  EXPECT_FLOAT_EQ(log.scans[0].ranges[90], 3.0f);
  EXPECT_FLOAT_EQ(log.scans[1].ranges[90], 1.2f);
  ASSERT_TRUE(log.laser_mount.has_value());
  EXPECT_NEAR(log.laser_mount->x, 0.25, 1e-4);  // the L line's laser pose, 25 cm ahead
  ASSERT_EQ(log.odometry.size(), 4u);           // two O lines and the two L lines' own poses
  EXPECT_NEAR(log.odometry[3].pose.x, 40.2, 1e-9);
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    EXPECT_GT(log.odometry[i].utime, log.odometry[i - 1].utime);
  }
}

TEST(DatasetImport, MinesExcerptIntegratesTheWheelTicks) {
  ImportOptions options;
  options.format = DatasetFormat::kMines;
  const ImportedLog log = import_dataset(excerpt("mines.dat"), options);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.malformed, 1);
  ASSERT_EQ(log.ticks.size(), 2u);
  EXPECT_EQ(log.ticks[1].right, 400);
  ASSERT_EQ(log.odometry.size(), 2u);
  // 200 and 300 ticks of 2000 per turn on 77 mm wheels, 330 mm apart.
  const double left = 200.0 / 2000.0 * 2 * std::numbers::pi * 0.077;
  const double right = 300.0 / 2000.0 * 2 * std::numbers::pi * 0.077;
  const Pose2 end = log.odometry[1].pose;
  EXPECT_NEAR(end.theta, (right - left) / 0.33, 1e-9);
  EXPECT_NEAR(std::hypot(end.x, end.y), (left + right) / 2, 1e-4);  // a chord of the arc
  EXPECT_GT(end.y, 0.0);
  EXPECT_NEAR(log.laser_mount->x, 0.145, 1e-12);
  EXPECT_FLOAT_EQ(log.scans[1].ranges[341], 2.1f);
  EXPECT_TRUE(std::isinf(log.scans[1].ranges[3]));
}

}  // namespace
}  // namespace slamer

namespace slamer {
namespace {

TEST(DatasetImport, StandingRawLogIsNotTakenForCorrected) {
  // A raw CARMEN log of a robot standing still: each next ODOM equals the scan's pose, but comes later.
  const std::string path = (std::filesystem::temp_directory_path() / "slamer_raw_standing.log").string();
  {
    std::ofstream out(path);
    for (int k = 0; k < 5; ++k) {
      const double t = 20.0 + 0.2 * k;
      out << "FLASER 3 1 1 1 0.5 0.5 0.1 0.5 0.5 0.1 " << t << " h " << t << "\n";
      out << "ODOM 0.5 0.5 0.1 0 0 0 " << t + 0.1 << " h " << t + 0.1 << "\n";
    }
  }
  const ImportedLog log = import_dataset(path, {});
  EXPECT_FALSE(log.corrected);
  EXPECT_TRUE(log.reference.empty());
  ASSERT_EQ(log.odometry.size(), 5u);
  EXPECT_EQ(log.odometry[0].utime, 20'100'000);  // the ODOM lines' own times
  EXPECT_EQ(log.scans[4].utime, 20'800'000);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace slamer

#include "tools/datasets/dataset_scans.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace slamer {
namespace {

std::string carmen_line(int n, const std::string& value) {
  std::string line = "FLASER " + std::to_string(n);
  for (int i = 0; i < n; ++i) {
    line += " " + value;
  }
  return line + " 1.0 2.0 0.5 1.0 2.0 0.5 1234.5 nohost 1234.6";
}

TEST(DatasetScans, CarmenLines) {
  LaserScan scan;
  ASSERT_TRUE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(180, "2.5"), &scan));
  ASSERT_EQ(scan.ranges.size(), 180u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 2.5f);
  EXPECT_DOUBLE_EQ(scan.angle_min, -std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(scan.angle_increment, std::numbers::pi / 180);
  EXPECT_EQ(scan.utime, 1'234'500'000);
  ASSERT_TRUE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(360, "81.91"), &scan));
  EXPECT_TRUE(std::isinf(scan.ranges[5]));  // fr079's "no return"
  ASSERT_TRUE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(180, "50"), &scan));
  EXPECT_TRUE(std::isinf(scan.ranges[5]));  // aces saturates at 50 m
}

TEST(DatasetScans, MalformedLinesAreRejected) {
  LaserScan scan;
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, "FLASER 180 1 2 3", &scan));  // truncated
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(180, "2.5x"), &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(180, "nan"), &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, carmen_line(180, "-1"), &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, "FLASER 99999999 1", &scan));
  std::string far_future = carmen_line(180, "2.5");
  far_future.replace(far_future.find("1234.5"), 6, "7.7e19");  // found by the fuzzer: overflowed the utime
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, far_future, &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCarmen, "ODOM 1 2 3", &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kCmu, "L 1 2 3", &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kMines, "12 13", &scan));
  EXPECT_FALSE(parse_dataset_line(DatasetFormat::kMines, "", &scan));
}

TEST(DatasetScans, CmuAndMines) {
  std::string cmu = "L -94.2 -139.9 -1.34 -88.5 -164.3 -1.34";
  for (int i = 0; i < 180; ++i) {
    cmu += i == 0 ? " 8183" : " 250";
  }
  cmu += " 0.025";
  LaserScan scan;
  ASSERT_TRUE(parse_dataset_line(DatasetFormat::kCmu, cmu, &scan));
  EXPECT_TRUE(std::isinf(scan.ranges[0]));
  EXPECT_FLOAT_EQ(scan.ranges[1], 2.5f);
  std::string mines = "212387282";
  for (int i = 1; i < 24; ++i) {
    mines += " 0";
  }
  for (int i = 0; i < 682; ++i) {
    mines += i == 3 ? " 0" : " 1500";
  }
  mines += " 0";
  ASSERT_TRUE(parse_dataset_line(DatasetFormat::kMines, mines, &scan));
  ASSERT_EQ(scan.ranges.size(), 682u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.5f);
  EXPECT_TRUE(std::isinf(scan.ranges[3]));
  EXPECT_EQ(scan.utime, 212387282);
}

TEST(DatasetScans, FilesCountBadLines) {
  const std::string path = (std::filesystem::temp_directory_path() / "slamer_dataset_test.log").string();
  std::ofstream(path) << "# comment\nPARAM x 1\n"
                      << carmen_line(180, "3.0") << "\nFLASER 180 1 2\n"
                      << carmen_line(180, "4.0") << "\n";
  const DatasetScans scans = read_dataset(path, DatasetFormat::kCarmen);
  ASSERT_EQ(scans.scans.size(), 2u);
  EXPECT_EQ(scans.bad_lines, 1);
  EXPECT_EQ(scans.scans[1].seq, 1);
  EXPECT_THROW(read_dataset("/nonexistent/x.log", DatasetFormat::kCarmen), std::runtime_error);
  std::filesystem::remove(path);
}

TEST(DatasetScans, RealDatasetsWhenPresent) {
  const std::string path =
      std::string(SLAMER_SOURCE_DIR "/../shared/datasets/ple_carmen_corrected/aces-corrected.log.gz");
  if (!std::filesystem::exists(path)) {
    GTEST_SKIP() << "../shared/datasets is absent";
  }
  const DatasetScans scans = read_dataset(path, DatasetFormat::kCarmen, 100);
  EXPECT_EQ(scans.scans.size(), 100u);
  EXPECT_EQ(scans.bad_lines, 0);
  EXPECT_EQ(scans.scans[0].ranges.size(), 180u);
}

}  // namespace
}  // namespace slamer

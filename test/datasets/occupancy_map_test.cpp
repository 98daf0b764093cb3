// slamer-mapgen's ray-cast map on scans of a known box room, loaded back
// through the stack's map loader.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include "common/map/semantic_map.hpp"
#include "tools/datasets/occupancy_map.hpp"
#include "tools/datasets/wean_map.hpp"

namespace slamer {
namespace {

// Walls at x = 0.02 and 4.02, y = 0.02 and 3.02 (inside cells, not on their edges).
LaserScan box_scan(const Pose2& laser) {
  LaserScan scan;
  scan.angle_min = -std::numbers::pi / 2;
  scan.angle_increment = std::numbers::pi / 180;
  scan.range_min = 0.02f;
  scan.range_max = 30.0f;
  for (int i = 0; i < 180; ++i) {
    const double a = laser.theta + scan.angle(static_cast<std::size_t>(i));
    const double c = std::cos(a);
    const double s = std::sin(a);
    double r = std::numeric_limits<double>::infinity();
    if (std::abs(c) > 1e-9) {
      r = std::min(r, ((c > 0 ? 4.02 : 0.02) - laser.x) / c);
    }
    if (std::abs(s) > 1e-9) {
      r = std::min(r, ((s > 0 ? 3.02 : 0.02) - laser.y) / s);
    }
    scan.ranges.push_back(i == 45 ? std::numeric_limits<float>::infinity() : static_cast<float>(r));
  }
  return scan;
}

TEST(OccupancyMap, BoxRoomLoadsAsASemanticMap) {
  std::vector<LaserScan> scans;
  std::vector<Pose2> poses;
  MapgenOptions options;
  options.laser_mount = {0.1, 0.0, 0.0};
  for (int k = 0; k < 8; ++k) {
    const Pose2 base{1.0 + 0.25 * k, 1.5, k * std::numbers::pi / 4};
    poses.push_back(base);
    scans.push_back(box_scan(compose(base, options.laser_mount)));
  }
  const OccupancyCounts counts = build_occupancy(scans, poses, options);
  const std::string dir = (std::filesystem::temp_directory_path() / "slamer_mapgen_test").string();
  write_occupancy_map(counts, options, dir);
  const SemanticMap map = load_semantic_map(dir + "/map.yaml");
  ASSERT_EQ(map.classes.size(), 1u);
  EXPECT_EQ(map.classes[0].name, "others");
  const auto at = [&](double x, double y) {
    const auto cell = map.geometry.cell_at({x, y});
    EXPECT_TRUE(cell.has_value()) << x << " " << y;
    return map.occupancy[map.geometry.index(cell->x, cell->y)];
  };
  EXPECT_EQ(at(0.02, 1.5), Occupancy::kOccupied);
  EXPECT_EQ(at(4.02, 2.0), Occupancy::kOccupied);
  EXPECT_EQ(at(2.0, 3.02), Occupancy::kOccupied);
  EXPECT_EQ(at(2.0, 1.5), Occupancy::kFree);
  EXPECT_EQ(at(3.5, 0.5), Occupancy::kFree);
  EXPECT_EQ(at(-0.5, 1.5), Occupancy::kUnknown);  // behind the wall, inside the 1 m margin
  const auto wall = map.geometry.cell_at({0.02, 1.5});
  EXPECT_EQ(map.labels[map.geometry.index(wall->x, wall->y)], 0);  // class "others"
  // The origin is the corner of the lower-left cell, a whole number of cells from the data.
  EXPECT_NEAR(std::remainder(map.geometry.origin.x, 0.05), 0.0, 1e-9);
  EXPECT_THROW(build_occupancy(scans, {}, options), std::invalid_argument);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slamer

namespace slamer {
namespace {

TEST(WeanMap, ProbabilitiesOfFreeBecomeCellsColumnByColumn) {
  const std::string excerpt = std::string(SLAMER_SOURCE_DIR) + "/test/datasets/excerpts/wean_map.dat";
  const GridCells map = read_wean_map(excerpt);
  ASSERT_EQ(map.geometry.width, 4);
  ASSERT_EQ(map.geometry.height, 3);
  EXPECT_DOUBLE_EQ(map.geometry.resolution, 0.1);
  const auto at = [&](int x, int y) { return map.cells[map.geometry.index(x, y)]; };
  EXPECT_EQ(at(0, 0), Occupancy::kUnknown);   // -1
  EXPECT_EQ(at(1, 0), Occupancy::kOccupied);  // P(free) 0
  EXPECT_EQ(at(2, 0), Occupancy::kUnknown);   // 0.5: neither
  EXPECT_EQ(at(3, 0), Occupancy::kFree);
  EXPECT_EQ(at(1, 1), Occupancy::kOccupied);  // 0.3
  EXPECT_EQ(at(2, 1), Occupancy::kFree);      // 0.81
  EXPECT_EQ(at(0, 1), Occupancy::kFree);      // file line i is the column x = i, its k-th number y = k
  EXPECT_EQ(at(3, 1), Occupancy::kUnknown);
  EXPECT_EQ(at(3, 2), Occupancy::kOccupied);
  const std::string dir = (std::filesystem::temp_directory_path() / "slamer_wean_map_test").string();
  write_grid_map(map.geometry, map.cells, "test", dir);
  const SemanticMap loaded = load_semantic_map(dir + "/map.yaml");
  EXPECT_EQ(loaded.occupancy, map.cells);
  std::filesystem::remove_all(dir);
  // Truncated and corrupt files: one error naming the file and line.
  const std::string bad = (std::filesystem::temp_directory_path() / "slamer_wean_bad.dat").string();
  std::ofstream(bad) << "global_map[0]: 4 3\n-1 0 0.5 1\n0.9 x 0.8 1\n";
  try {
    read_wean_map(bad);
    ADD_FAILURE() << "a corrupt map was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("slamer_wean_bad.dat:3: cell 1"), std::string::npos) << e.what();
  }
  std::ofstream(bad) << "global_map[0]: 4 3\n-1 0 0.5 1\n";
  EXPECT_THROW(read_wean_map(bad), std::runtime_error);
  std::filesystem::remove(bad);
}

}  // namespace
}  // namespace slamer

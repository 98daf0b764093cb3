#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "common/config/config_reader.hpp"
#include "common/map/distance_field.hpp"
#include "common/map/semantic_map.hpp"

#include "test/support/child_process.hpp"
#include "test/support/temp_dir.hpp"

namespace slamer {
namespace {

using test::TempDir;

std::string load_error(const std::string& yaml_path) {
  try {
    load_semantic_map(yaml_path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(GridGeometry, CellsWithRotatedOrigin) {
  GridGeometry g{10, 5, 0.5, {1.0, 2.0, std::numbers::pi / 2}};
  // Cell (0, 0)'s corner is at (1, 2); the grid's x axis points along world +y.
  const auto c = g.cell_at({0.9, 2.1});
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(*c, (Cell{0, 0}));
  const auto far = g.cell_at({0.9 - 0.5 * 4, 2.1 + 0.5 * 9});
  ASSERT_TRUE(far.has_value());
  EXPECT_EQ(*far, (Cell{9, 4}));
  EXPECT_FALSE(g.cell_at({1.1, 2.1}).has_value());  // behind the origin along grid y
  EXPECT_FALSE(g.cell_at({0.9, 2.1 + 5.0}).has_value());
  EXPECT_FALSE(g.cell_at({std::nan(""), 2.1}).has_value());
  const Eigen::Vector2d center = g.cell_center(3, 1);
  EXPECT_EQ(*g.cell_at(center), (Cell{3, 1}));
  EXPECT_NEAR(center.x(), 1.0 - 0.75, 1e-12);
  EXPECT_NEAR(center.y(), 2.0 + 1.75, 1e-12);
}

TEST(DistanceField, MatchesBruteForceWithinHalfALevel) {
  std::mt19937 rng(11);
  // Grids taller than a band (32 rows) and reaches shorter than the grid check the bands' margins.
  for (const auto& [w, h, density] : std::vector<std::tuple<int, int, double>>{{1, 1, 1.0},
                                                                               {1, 37, 0.1},
                                                                               {53, 1, 0.05},
                                                                               {40, 31, 0.02},
                                                                               {64, 64, 0.001},
                                                                               {97, 45, 0.3},
                                                                               {70, 150, 0.003},
                                                                               {33, 100, 0.01}}) {
    for (const double max_distance : {0.3, 2.0, 12.0}) {
      GridGeometry g{w, h, 0.05, {}};
      std::vector<uint8_t> target(g.size());
      std::bernoulli_distribution pick(density);
      for (uint8_t& t : target) {
        t = pick(rng) ? 1 : 0;
      }
      target[static_cast<std::size_t>(rng() % g.size())] = 1;
      const DistanceField field(g, target, max_distance);
      ASSERT_TRUE(field.has_targets());
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          double best = std::numeric_limits<double>::infinity();
          for (int ty = 0; ty < h; ++ty) {
            for (int tx = 0; tx < w; ++tx) {
              if (target[g.index(tx, ty)] != 0) {
                best = std::min(best, std::hypot(tx - x, ty - y) * 0.05);
              }
            }
          }
          ASSERT_NEAR(field.at(x, y), std::min(best, max_distance), field.step() / 2 + 1e-6)
              << w << "x" << h << " reach " << max_distance << " at " << x << "," << y;
        }
      }
    }
  }
}

TEST(DistanceField, DiagonalIsEuclideanNotChamfer) {
  GridGeometry g{200, 200, 0.1, {}};
  std::vector<uint8_t> target(g.size(), 0);
  target[g.index(0, 0)] = 1;
  const DistanceField field(g, target, 30.0);
  EXPECT_NEAR(field.at(150, 80), std::hypot(150.0, 80.0) * 0.1, field.step() / 2);
  EXPECT_NEAR(field.at(60, 199), std::hypot(60.0, 199.0) * 0.1, field.step() / 2);
  EXPECT_NEAR(field.at(199, 199), std::hypot(199.0, 199.0) * 0.1, field.step() / 2);
  const DistanceField short_reach(g, target, 10.0);
  EXPECT_EQ(short_reach.level(199, 199), DistanceField::kSaturated);
  EXPECT_FLOAT_EQ(short_reach.at(199, 199), 10.0f);
}

TEST(DistanceField, NoTargetIsSaturatedAndOffMapIsExplicit) {
  GridGeometry g{5, 5, 1.0, {}};
  const DistanceField field(g, std::vector<uint8_t>(g.size(), 0), 3.0);
  EXPECT_FALSE(field.has_targets());
  EXPECT_FLOAT_EQ(field.at(2, 2), 3.0f);
  EXPECT_FALSE(field.at_world({-0.5, 1.0}).has_value());
  EXPECT_TRUE(field.at_world({0.5, 1.0}).has_value());
}

TEST(DistanceField, TilesFarFromTargetsShareOneBlock) {
  // 256 x 256 cells = 64 tiles; one target in a corner reaches 1 m = 20 cells: only its own tile varies.
  GridGeometry g{256, 256, 0.05, {}};
  std::vector<uint8_t> target(g.size(), 0);
  target[g.index(3, 4)] = 1;
  const DistanceField field(g, target, 1.0);
  EXPECT_EQ(field.distinct_tiles(), 1u);
  EXPECT_LT(field.memory_bytes(), g.size() / 4);
  EXPECT_EQ(field.level(200, 200), DistanceField::kSaturated);
  EXPECT_NEAR(field.at(3, 20), 16 * 0.05, field.step() / 2);
  // A checkerboard of targets: every tile varies, and it still costs about a byte a cell.
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      target[g.index(x, y)] = ((x / 8 + y / 8) % 2 == 0 && x % 8 == 0) ? 1 : 0;
    }
  }
  const DistanceField dense(g, target, 1.0);
  EXPECT_EQ(dense.distinct_tiles(), 64u);
  EXPECT_LT(dense.memory_bytes(), g.size() * 2);
}

TEST(DistanceField, RejectsBadArguments) {
  GridGeometry g{4, 4, 0.05, {}};
  EXPECT_THROW(DistanceField(g, std::vector<uint8_t>(15, 0), 1.0), std::invalid_argument);
  EXPECT_THROW(DistanceField(g, std::vector<uint8_t>(16, 0), 0.0), std::invalid_argument);
  EXPECT_THROW(DistanceField(g, std::vector<uint8_t>(16, 0), std::numeric_limits<double>::infinity()),
               std::invalid_argument);
}

// A 4x3 map image, top row first, as map_server reads it.
void write_occupancy_pgm(const std::string& path) {
  cv::Mat image(3, 4, CV_8UC1);
  const uint8_t rows[3][4] = {{0, 254, 205, 100}, {254, 254, 254, 254}, {0, 0, 254, 160}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      image.at<uint8_t>(r, c) = rows[r][c];
    }
  }
  ASSERT_TRUE(cv::imwrite(path, image));
}

TEST(SemanticMap, MapServerOccupancyWithThresholdsNegateAndYaw) {
  TempDir dir("slamer_map_test");
  write_occupancy_pgm(dir.file("map.pgm"));
  dir.write("map.yaml",
            "image: map.pgm\nresolution: 0.1\norigin: [-1.0, 2.0, 0.5]\noccupied_thresh: 0.65\n"
            "free_thresh: 0.196\nnegate: 0\n");
  const SemanticMap map = load_semantic_map(dir.file("map.yaml"));
  ASSERT_EQ(map.geometry.width, 4);
  ASSERT_EQ(map.geometry.height, 3);
  EXPECT_DOUBLE_EQ(map.geometry.resolution, 0.1);
  EXPECT_DOUBLE_EQ(map.geometry.origin.theta, 0.5);
  const auto at = [&](int x, int y) { return map.occupancy[map.geometry.index(x, y)]; };
  // Top image row is grid row 2. 0 -> occupied, 254 -> free, 205 -> unknown,
  // 100 -> p = 0.61 (unknown), 160 -> p = 0.37 (unknown).
  EXPECT_EQ(at(0, 2), Occupancy::kOccupied);
  EXPECT_EQ(at(1, 2), Occupancy::kFree);
  EXPECT_EQ(at(2, 2), Occupancy::kUnknown);
  EXPECT_EQ(at(3, 2), Occupancy::kUnknown);
  EXPECT_EQ(at(0, 0), Occupancy::kOccupied);
  EXPECT_EQ(at(3, 0), Occupancy::kUnknown);
  EXPECT_TRUE(map.classes.empty());

  dir.write("negated.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\n");
  const SemanticMap negated = load_semantic_map(dir.file("negated.yaml"));
  EXPECT_EQ(negated.occupancy[negated.geometry.index(0, 2)], Occupancy::kFree);
  EXPECT_EQ(negated.occupancy[negated.geometry.index(1, 2)], Occupancy::kOccupied);

  const DistanceField obstacles = obstacle_distance_field(map, 2.55);  // 0.01 m a level
  EXPECT_NEAR(obstacles.at(1, 0), 0.0, 1e-6);                          // bottom image row: 0, 0, 254, 160
  EXPECT_NEAR(obstacles.at(2, 0), 0.1, 1e-6);
  EXPECT_NEAR(obstacles.at(3, 1), std::hypot(2.0, 1.0) * 0.1, 0.005);
}

void write_semantic_png(const std::string& path) {
  // BGR in OpenCV. Row 0 (top): door (255,0,255), glass (0,255,255), free, odd colour.
  cv::Mat image(3, 4, CV_8UC3, cv::Scalar(254, 254, 254));
  image.at<cv::Vec3b>(0, 0) = {255, 0, 255};
  image.at<cv::Vec3b>(0, 1) = {255, 255, 0};
  image.at<cv::Vec3b>(0, 3) = {10, 20, 30};
  image.at<cv::Vec3b>(2, 3) = {10, 20, 30};
  ASSERT_TRUE(cv::imwrite(path, image));
}

TEST(SemanticMap, SemanticLayerWithClassTable) {
  TempDir dir("slamer_map_test");
  write_occupancy_pgm(dir.file("map.pgm"));
  write_semantic_png(dir.file("semantic.png"));
  dir.write("map.yaml",
            "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
            "semantic:\n  image: semantic.png\n  classes:\n"
            "    - {name: door, color: [255, 0, 255]}\n"
            "    - {name: glass_door, color: [0, 255, 255]}\n"
            "    - {name: others, color: [0, 0, 0]}\n");
  const SemanticMap map = load_semantic_map(dir.file("map.yaml"));
  ASSERT_EQ(map.classes.size(), 3u);
  const auto label = [&](int x, int y) { return map.labels[map.geometry.index(x, y)]; };
  EXPECT_EQ(label(0, 2), map.class_index("door"));
  EXPECT_EQ(label(1, 2), map.class_index("glass_door"));
  EXPECT_EQ(label(1, 1), -1);                         // free
  EXPECT_EQ(label(0, 0), map.class_index("others"));  // occupied, no colour -> others
  EXPECT_EQ(map.unknown_color_cells, 2);
  ASSERT_EQ(map.warnings.size(), 1u);
  EXPECT_NE(map.warnings[0].find("2 semantic pixels in 1 colour(s) of no class (most: [30, 20, 10] x 2)"),
            std::string::npos)
      << map.warnings[0];
  const std::vector<DistanceField> fields = class_distance_fields(map, 2.55);
  ASSERT_EQ(fields.size(), 3u);
  EXPECT_NEAR(fields[static_cast<std::size_t>(map.class_index("door"))].at(3, 0), std::hypot(3.0, 2.0) * 0.1, 0.005);
  const DistanceField free = free_space_distance_field(map, 2.55);
  EXPECT_NEAR(free.at(1, 1), 0.0, 1e-6);  // free, no class
  EXPECT_NEAR(free.at(0, 2), 0.1, 1e-6);  // the door, next to free (1, 2)
}

// A free 3 m x 0.5 m strip at 0.1 m with a no-entry line across it at x = 1.0 m
// and, with `door`, a door across it at x = 2.0 m.
SemanticMap strip(bool door) {
  SemanticMap map;
  map.geometry.width = 30;
  map.geometry.height = 5;
  map.geometry.resolution = 0.1;
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  map.classes.push_back({"no_entry_line", {255, 0, 0}});
  if (door) {
    map.classes.push_back({"door", {255, 0, 255}});
  }
  for (int y = 0; y < 5; ++y) {
    map.labels[map.geometry.index(10, y)] = 0;
    if (door) {
      map.labels[map.geometry.index(20, y)] = 1;
    }
  }
  return map;
}

TEST(SemanticMap, FreeSpaceWithAMarginStaysClearOfClassedCells) {
  const SemanticMap map = strip(false);
  const DistanceField adjacent = free_space_distance_field(map, 2.55);
  EXPECT_NEAR(adjacent.at(10, 2), 0.1, 0.006);  // the line is one cell from free space
  EXPECT_NEAR(adjacent.at(12, 2), 0.0, 1e-6);
  // With 0.25 m, free space starts 0.3 m from the line (cells 7 and 13).
  const DistanceField clear = free_space_distance_field(map, 2.55, 0.25);
  EXPECT_NEAR(clear.at(10, 2), 0.3, 0.006);
  EXPECT_NEAR(clear.at(12, 2), 0.1, 0.006);
  EXPECT_NEAR(clear.at(13, 2), 0.0, 1e-6);
  EXPECT_NEAR(clear.at(7, 2), 0.0, 1e-6);
  EXPECT_NEAR(clear.at(0, 0), 0.0, 1e-6);
}

// The strip with its door: a margin of the no-entry line's own keeps free space
// further from it, the door keeps the common one.
TEST(SemanticMap, AClassWithAMarginOfItsOwnKeepsFreeSpaceThatFarOff) {
  const SemanticMap map = strip(true);
  const DistanceField common = free_space_distance_field(map, 2.55, 0.25, {});
  const DistanceField own = free_space_distance_field(map, 2.55, 0.25, {0.45, 0.0});
  // Common 0.25 m: free from 0.3 m off either line (cells 7, 13, 17, 23).
  EXPECT_NEAR(common.at(10, 2), 0.3, 0.006);
  EXPECT_NEAR(common.at(7, 2), 0.0, 1e-6);
  EXPECT_NEAR(common.at(13, 2), 0.0, 1e-6);
  // 0.45 m for the no-entry line: free from 0.5 m off it (cells 5 and 15), the door's unchanged.
  EXPECT_NEAR(own.at(10, 2), 0.5, 0.006);
  EXPECT_NEAR(own.at(7, 2), 0.2, 0.006);
  EXPECT_NEAR(own.at(15, 2), 0.0, 1e-6);
  EXPECT_NEAR(own.at(20, 2), 0.3, 0.006);
  EXPECT_NEAR(own.at(17, 2), 0.0, 1e-6);
  // A margin of its own without a common one still keeps free space off that class only.
  const DistanceField only = free_space_distance_field(map, 2.55, 0.0, {0.25, 0.0});
  EXPECT_NEAR(only.at(10, 2), 0.3, 0.006);
  EXPECT_NEAR(only.at(19, 2), 0.0, 1e-6);
  EXPECT_NEAR(only.at(20, 2), 0.1, 0.006);
}

TEST(SemanticMap, IsmYamlFormat) {
  TempDir dir("slamer_map_test");
  write_occupancy_pgm(dir.file("ogm.pgm"));
  write_semantic_png(dir.file("ism.png"));
  dir.write("ogm.yaml",
            "image: ogm.pgm\nresolution: 0.05\norigin: [1, 1, 0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  dir.write("ism.yaml",
            "image: ism.png\nogm_info_yaml: ogm.yaml\nobjects: [door, glass_door, do_not_enter_line, others]\n"
            "door_color: [255, 0, 255]\nglass_door_color: [0, 255, 255]\ndo_not_enter_line_color: [30, 20, 10]\n"
            "others_color: [0, 0, 0]\n");
  const SemanticMap map = load_semantic_map(dir.file("ism.yaml"));
  EXPECT_DOUBLE_EQ(map.geometry.resolution, 0.05);
  EXPECT_DOUBLE_EQ(map.geometry.origin.x, 1.0);
  ASSERT_EQ(map.classes.size(), 4u);
  // ism.yaml's do_not_enter_line is the project's no_entry_line, its colour read from its own key.
  EXPECT_EQ(map.classes[2].name, "no_entry_line");
  EXPECT_EQ(map.classes[2].rgb, (std::array<uint8_t, 3>{30, 20, 10}));
  EXPECT_EQ(map.class_index("do_not_enter_line"), -1);
  EXPECT_EQ(map.labels[map.geometry.index(3, 2)], map.class_index("no_entry_line"));
  EXPECT_EQ(map.labels[map.geometry.index(0, 0)], map.class_index("others"));
  EXPECT_EQ(map.unknown_color_cells, 0);

  dir.write("both.yaml",
            "image: ism.png\nogm_info_yaml: ogm.yaml\nobjects: [door, do_not_enter_line, no_entry_line]\n"
            "door_color: [255, 0, 255]\ndo_not_enter_line_color: [30, 20, 10]\nno_entry_line_color: [255, 0, 0]\n");
  EXPECT_EQ(load_error(dir.file("both.yaml")),
            dir.file("both.yaml") +
                ":3: key 'objects': lists both do_not_enter_line and no_entry_line, which are one class here");
}

TEST(SemanticMap, BadMapsGiveOneLineNamingFileAndProblem) {
  TempDir dir("slamer_map_test");
  write_occupancy_pgm(dir.file("map.pgm"));
  write_semantic_png(dir.file("semantic.png"));
  const std::string yaml = dir.file("bad.yaml");

  dir.write("bad.yaml", "image: missing.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': image '" + dir.file("missing.pgm") + "' does not exist");

  dir.write("bad.yaml", "image: map.pgm\nresolution: 0\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":2: key 'resolution': expected a number > 0, got '0'");

  dir.write("bad.yaml", "image: map.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":2: key 'resolution': expected a number > 0, got '-0.05'");

  dir.write("bad.yaml", "image: map.pgm\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'resolution': missing (this key is required)");

  dir.write("bad.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":3: key 'origin': expected a list of 3 numbers, got 2");

  dir.write("bad.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0\n");
  EXPECT_EQ(load_error(yaml).rfind(yaml + ":4: YAML syntax error", 0), 0u) << load_error(yaml);

  EXPECT_EQ(load_error(dir.file("nope.yaml")), dir.file("nope.yaml") + ": cannot open: No such file or directory");

  dir.write("garbage.png", "this is not a png");
  dir.write("bad.yaml", "image: garbage.png\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml),
            yaml + ":1: key 'image': image '" + dir.file("garbage.png") + "' is not a PGM/PPM or PNG file");
  dir.write("truncated.png", std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16));
  dir.write("bad.yaml", "image: truncated.png\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': cannot decode image '" + dir.file("truncated.png") +
                                  "' (not a PGM/PNG OpenCV can read?)");

  // A map_server PGM cut in half (a copy that did not finish): said before OpenCV prints lines of its own.
  const std::string whole = test::read_file(dir.file("map.pgm"));
  dir.write("cut.pgm", whole.substr(0, whole.size() - 5));
  dir.write("bad.yaml", "image: cut.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': image '" + dir.file("cut.pgm") +
                                  "' is cut short: 4 x 3 pixels need 12 bytes, the file has 7");
  dir.write("header.pgm", "P5\n4 x\n255\n");
  dir.write("bad.yaml", "image: header.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': image '" + dir.file("header.pgm") + "' has a damaged header");
  // A side no map has (the size would overflow): the same line (a fuzzer's find).
  dir.write("header.pgm", "P5\n488888888888885\n48845\n255\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': image '" + dir.file("header.pgm") + "' has a damaged header");
  dir.write("header.pgm", "P5\n4 3\n70000\n");
  EXPECT_EQ(load_error(yaml), yaml + ":1: key 'image': image '" + dir.file("header.pgm") + "' has a damaged header");

  cv::imwrite(dir.file("small.png"), cv::Mat(2, 2, CV_8UC3, cv::Scalar(254, 254, 254)));
  dir.write("bad.yaml",
            "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nsemantic:\n  image: small.png\n"
            "  classes: [{name: door, color: [255, 0, 255]}]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":5: key 'semantic.image': semantic image is 2x2 but the occupancy image is 4x3");

  dir.write("bad.yaml",
            "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nsemantic:\n  image: semantic.png\n"
            "  classes: [{name: door, color: [255, 0, 255]}, {name: gate, color: [255, 0, 255]}]\n");
  EXPECT_EQ(load_error(yaml), yaml + ":6: key 'semantic.classes': classes 'door' and 'gate' share a colour");

  dir.write("bad.yaml",
            "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nsemantic:\n  image: semantic.png\n"
            "  classes: [{name: door, color: [254, 254, 254]}]\n");
  EXPECT_EQ(load_error(yaml),
            yaml + ":6: key 'semantic.classes': class 'door' uses a colour reserved for unknown/free space");

  dir.write("bad.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.9\n");
  EXPECT_EQ(load_error(yaml), yaml + ":4: key 'free_thresh': must not exceed occupied_thresh (0.650000)");

  dir.write("bad.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nresolutoin: 0.2\n");
  EXPECT_EQ(load_error(yaml), yaml + ":4: unknown key 'resolutoin'");

  cv::imwrite(dir.file("deep.png"), cv::Mat(3, 4, CV_16UC1, cv::Scalar(1000)));
  dir.write("bad.yaml", "image: deep.png\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(load_error(yaml),
            yaml + ":1: key 'image': image '" + dir.file("deep.png") + "' has 16-bit channels; 8-bit expected");

  dir.write("ism.yaml", "image: semantic.png\nogm_info_yaml: map.yaml\nobjects: [door]\n");
  EXPECT_EQ(load_error(dir.file("ism.yaml")),
            dir.file("ism.yaml") + ":1: key 'door_color': missing (this key is required)");
}

}  // namespace
}  // namespace slamer

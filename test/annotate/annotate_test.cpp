// slamer-annotate-map's library: which cells an object paints (numeric
// checks on cells), the objects file's one-line errors, and the written map
// as the localizer loads and uses it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "common/config/config_reader.hpp"
#include "localizer/localizer_node.hpp"
#include "localizer/particle_filter.hpp"
#include "tools/annotate/annotate.hpp"
#include "tools/annotate/object_cells.hpp"

namespace slamer {
namespace {

GridGeometry grid(int width, int height, double resolution, Pose2 origin = {}) {
  GridGeometry g;
  g.width = width;
  g.height = height;
  g.resolution = resolution;
  g.origin = origin;
  return g;
}

MapObject line(std::vector<Eigen::Vector2d> points, std::optional<double> thickness = std::nullopt) {
  MapObject o;
  o.class_name = "door";
  o.points = std::move(points);
  o.thickness = thickness;
  return o;
}

MapObject polygon(std::vector<Eigen::Vector2d> points, std::optional<double> thickness = std::nullopt) {
  MapObject o = line(std::move(points), thickness);
  o.shape = ObjectShape::kPolygon;
  return o;
}

std::vector<std::size_t> cells_in(const GridGeometry& g, int x0, int y0, int x1, int y1) {
  std::vector<std::size_t> cells;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      cells.push_back(g.index(x, y));
    }
  }
  return cells;
}

TEST(ObjectCells, AThinLineIsOneCellWideAndEndsAtItsPoints) {
  const GridGeometry g = grid(20, 10, 0.1);
  // Along the centres of row 5, from the centre of column 2 to that of column 8.
  EXPECT_EQ(object_cells(line({{0.25, 0.55}, {0.85, 0.55}}), g), cells_in(g, 2, 5, 8, 5));
  // A thickness below a cell is one cell.
  EXPECT_EQ(object_cells(line({{0.25, 0.55}, {0.85, 0.55}}, 0.02), g), cells_in(g, 2, 5, 8, 5));
  // 45 degrees through the centres: the diagonal cells only (neighbours are 0.071 m > 0.05 m away).
  std::vector<std::size_t> diagonal;
  for (int i = 0; i < 10; ++i) {
    diagonal.push_back(g.index(i, i));
  }
  EXPECT_EQ(object_cells(line({{0.05, 0.05}, {0.95, 0.95}}), g), diagonal);
}

TEST(ObjectCells, AThickLineCoversCentresWithinHalfItsWidthWithRoundEnds) {
  const GridGeometry g = grid(20, 10, 0.1);
  // 0.3 m: rows 4..6 (0.1 m from the line), and at the round ends columns 1 and 9 (0.1 and 0.141 m).
  const auto cells = object_cells(line({{0.25, 0.55}, {0.85, 0.55}}, 0.3), g);
  EXPECT_EQ(cells, cells_in(g, 1, 4, 9, 6));
  // A polyline is its segments: an L, one cell wide.
  const auto l = object_cells(line({{0.25, 0.25}, {0.65, 0.25}, {0.65, 0.55}}), g);
  EXPECT_EQ(l.size(), 5u + 3u);
  EXPECT_EQ(l.front(), g.index(2, 2));
  EXPECT_EQ(l.back(), g.index(6, 5));
  // A centre exactly half the width away counts: a line on a cell boundary paints both sides.
  EXPECT_EQ(object_cells(line({{0.25, 0.5}, {0.45, 0.5}}), g), cells_in(g, 2, 4, 4, 5));
}

TEST(ObjectCells, APolygonIsFilledByItsCentresOrOutlinedWithAThickness) {
  const GridGeometry g = grid(20, 10, 0.1);
  // Box 0.2..0.6 x 0.2..0.5: centres 0.25..0.55 and 0.25..0.45.
  EXPECT_EQ(object_cells(polygon({{0.2, 0.2}, {0.6, 0.2}, {0.6, 0.5}, {0.2, 0.5}}), g), cells_in(g, 2, 2, 5, 4));
  // The triangle x + y < 1: centres with i + j <= 8, 45 cells, in either winding.
  EXPECT_EQ(object_cells(polygon({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}), g).size(), 45u);
  EXPECT_EQ(object_cells(polygon({{0.0, 1.0}, {1.0, 0.0}, {0.0, 0.0}}), g).size(), 45u);
  // Outlined through the centres of columns 2..7, rows 2..5: the ring of 16 cells, not the 8 inside.
  const auto ring = object_cells(polygon({{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.55}, {0.25, 0.55}}, 0.1), g);
  EXPECT_EQ(ring.size(), 16u);
  EXPECT_EQ(std::count(ring.begin(), ring.end(), g.index(3, 3)), 0);
  EXPECT_EQ(std::count(ring.begin(), ring.end(), g.index(7, 4)), 1);
}

TEST(ObjectCells, WorkInTheGridOfARotatedOriginAndClipAtTheEdge) {
  // Origin at (1, 2) turned 90 degrees: grid +x is world +y, grid +y is world -x.
  const GridGeometry g = grid(10, 10, 0.1, {1.0, 2.0, M_PI / 2});
  EXPECT_EQ(object_cells(line({{0.95, 2.05}, {0.95, 2.95}}), g), cells_in(g, 0, 0, 9, 0));
  // A 0.3 m stroke along the bottom row would cover rows -1..1: row -1 is off the map.
  const GridGeometry flat = grid(10, 10, 0.1);
  EXPECT_EQ(object_cells(line({{0.25, 0.05}, {0.45, 0.05}}, 0.3), flat), cells_in(flat, 1, 0, 5, 1));
}

struct TempDir {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("slamer_annotate_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { std::filesystem::create_directories(path); }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// A 6 m x 4 m map at 0.1 m: walls on the border, free inside.
SemanticMap walled_map() {
  SemanticMap map;
  map.geometry = grid(60, 40, 0.1);
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 60; ++x) {
      if (x == 0 || y == 0 || x == 59 || y == 39) {
        map.occupancy[map.geometry.index(x, y)] = Occupancy::kOccupied;
      }
    }
  }
  return map;
}

ObjectList objects(const std::string& yaml, const SemanticMap& map) {
  const ConfigReader reader = ConfigReader::from_string(yaml, "obj.yaml");
  ObjectList list = read_object_list(reader, map);
  reader.check_all_keys_used();
  return list;
}

std::string error(const std::string& yaml, const SemanticMap& map = walled_map()) {
  try {
    objects(yaml, map);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ObjectList, ReadsLinesPolygonsAndTheClassTable) {
  const ObjectList list = objects(
      "classes:\n  - {name: lift_door, color: [0, 128, 255]}\nobjects:\n"
      "  - {name: lab, class: door, line: [1, 1, 2, 1], thickness: 0.2, occupancy: occupied}\n"
      "  - {class: lift_door, polygon: [1, 2, 2, 2, 2, 3]}\n",
      walled_map());
  ASSERT_EQ(list.classes.size(), 6u);
  EXPECT_EQ(list.classes[0].name, "door");
  EXPECT_EQ(list.classes[4].name, "others");
  EXPECT_EQ(list.classes[5].name, "lift_door");
  ASSERT_EQ(list.objects.size(), 2u);
  EXPECT_EQ(list.objects[0].name, "lab");
  EXPECT_EQ(list.objects[0].shape, ObjectShape::kLine);
  EXPECT_DOUBLE_EQ(*list.objects[0].thickness, 0.2);
  EXPECT_EQ(list.objects[0].occupancy, CellOccupancy::kOccupied);
  EXPECT_EQ(list.objects[1].shape, ObjectShape::kPolygon);
  EXPECT_FALSE(list.objects[1].thickness);
  EXPECT_EQ(list.objects[1].points.size(), 3u);
  // The project's table is that of the bundled maps.
  const SemanticMap paper = load_semantic_map(std::string(SLAMER_SOURCE_DIR "/config/maps/paper_indoor/map.yaml"));
  ASSERT_EQ(paper.classes.size(), project_classes().size());
  for (std::size_t c = 0; c < paper.classes.size(); ++c) {
    EXPECT_EQ(paper.classes[c].name, project_classes()[c].name);
    EXPECT_EQ(paper.classes[c].rgb, project_classes()[c].rgb);
  }
}

TEST(ObjectList, EveryProblemIsOneLineNamingFileLineAndObject) {
  EXPECT_EQ(error("objects:\n  - {class: door, line: [1, 1, 2, 1]}\n  - {name: lab door, class: dor, line: [1, 1, 2, "
                  "1]}\n"),
            "obj.yaml:3: key 'objects[1].class': object 'lab door': unknown class 'dor' (the classes: door, "
            "glass_door, fence, no_entry_line, others; add others under 'classes:')");
  EXPECT_EQ(error("objects:\n  - {class: fence, polygon: [1, 1, 2, 1]}\n"),
            "obj.yaml:2: key 'objects[0].polygon': a polygon needs at least 3 points, got 2");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1]}\n"),
            "obj.yaml:2: key 'objects[0].line': a line needs at least 2 points, got 1");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2]}\n"),
            "obj.yaml:2: key 'objects[0].line': 3 numbers are not x, y pairs (x0, y0, x1, y1, ...)");
  EXPECT_EQ(error("objects:\n  - {name: gate, class: fence, line: [1, 1, 7, 1]}\n"),
            "obj.yaml:2: key 'objects[0].line': object 'gate': point 2 (7.000, 1.000) is outside the map (x 0.00 .. "
            "6.00, y 0.00 .. 4.00 m)");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, two, 1]}\n"),
            "obj.yaml:2: key 'objects[0].line[2]': expected a finite number, got 'two'");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, .nan, 1]}\n"),
            "obj.yaml:2: key 'objects[0].line[2]': expected a finite number, got '.nan'");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2, 1], thickness: -0.1}\n"),
            "obj.yaml:2: key 'objects[0].thickness': expected a number in [1e-06, 100], got '-0.1'");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2, 1], occupancy: closed}\n"),
            "obj.yaml:2: key 'objects[0].occupancy': expected one of keep, occupied, free, got 'closed'");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2, 1], polygon: [1, 1, 2, 1, 2, 2]}\n"),
            "obj.yaml:2: key 'objects[0].polygon': give either line or polygon, not both");
  EXPECT_EQ(error("objects:\n  - {class: fence}\n"),
            "obj.yaml:2: key 'objects[0].line': missing: give line or polygon (x0, y0, x1, y1, ...)");
  EXPECT_EQ(error("objects:\n  - {class: fence, polygon: [1, 1, 2, 2, 3, 3]}\n"),
            "obj.yaml:2: key 'objects[0].polygon': covers no cell (a polygon smaller than a cell, or with its points "
            "on one line?)");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2, 1], widht: 0.2}\n"),
            "obj.yaml:2: unknown key 'objects[0].widht'");
  EXPECT_EQ(error("objects:\n  - {class: fence, line: [1, 1, 2, 1}\n"),
            "obj.yaml:2: YAML syntax error: illegal flow end");
  EXPECT_EQ(error("classes:\n  - {name: door, color: [1, 2, 3]}\nobjects: []\n"),
            "obj.yaml:2: key 'classes[0].name': 'door' is already a class (door, glass_door, fence, no_entry_line, "
            "others)");
  EXPECT_EQ(error("classes:\n  - {name: lift, color: [255, 0, 255]}\nobjects: []\n"),
            "obj.yaml:2: key 'classes[0].color': class 'lift' has the colour of class 'door'");
  EXPECT_EQ(error("classes:\n  - {name: lift, color: [254, 254, 254]}\nobjects: []\n"),
            "obj.yaml:2: key 'classes[0].color': is reserved for unknown (205), free (254) or unlabelled (255) cells");
  EXPECT_EQ(error("classes: []\n"), "obj.yaml:1: key 'objects': missing (this key is required)");
}

TEST(ObjectList, AMapsOwnTableIsKeptAndTheProjectsClassesFitAroundIt) {
  SemanticMap map = walled_map();
  map.classes = {{"stairs: down", {255, 0, 0}}, {"door", {10, 10, 10}}};  // no_entry_line's colour, door's name
  const ObjectList list = objects("objects:\n  - {class: no_entry_line, line: [1, 1, 2, 1]}\n", map);
  ASSERT_EQ(list.classes.size(), 6u);
  EXPECT_EQ(list.classes[0].name, "stairs: down");
  EXPECT_EQ(list.classes[1].rgb, (std::array<uint8_t, 3>{10, 10, 10}));  // the map's door colour kept
  EXPECT_EQ(list.classes[4].name, "no_entry_line");
  EXPECT_EQ(list.classes[4].rgb, (std::array<uint8_t, 3>{255, 0, 1}));  // the next free colour
  // The written table loads back with the odd name.
  TempDir dir;
  map.labels[map.geometry.index(5, 5)] = 0;
  write_semantic_map(annotate_map(map, list), dir.path.string(), "a test");
  const SemanticMap loaded = load_semantic_map(dir.file("map.yaml"));
  EXPECT_EQ(loaded.labels[loaded.geometry.index(5, 5)], loaded.class_index("stairs: down"));
  EXPECT_EQ(loaded.labels[loaded.geometry.index(15, 10)], loaded.class_index("no_entry_line"));
  EXPECT_EQ(error("classes:\n  - {name: 'a b', color: [1, 2, 3]}\nobjects: []\n"),
            "obj.yaml:2: key 'classes[0].name': 'a b': a class name is letters, digits, '_', '-' and '.'");
}

TEST(AnnotateMap, PaintsClassesAndOccupancyInOrderOverTheMapsLabels) {
  SemanticMap map = walled_map();
  map.classes = {{"others", {0, 0, 0}}, {"fence", {1, 2, 3}}};  // an input table of its own
  map.labels[map.geometry.index(40, 30)] = 1;                   // a fence cell
  for (int y = 0; y < 40; ++y) {
    map.labels[map.geometry.index(0, y)] = 0;  // the west wall labelled, the others not
  }
  const ObjectList list = objects(
      "objects:\n"
      "  - {class: door, line: [2.05, 1.05, 2.05, 1.95], occupancy: occupied}\n"     // closed: 10 cells
      "  - {class: no_entry_line, line: [3.05, 0.05, 3.05, 3.95]}\n"                 // over the south and north walls
      "  - {class: glass_door, line: [2.05, 1.55, 2.55, 1.55], occupancy: free}\n",  // over the door's middle
      map);
  AnnotationSummary summary;
  const SemanticMap out = annotate_map(map, list, &summary);
  EXPECT_EQ(out.classes[0].name, "others");  // the map's table first, its colours kept
  EXPECT_EQ(out.classes[1].rgb, (std::array<uint8_t, 3>{1, 2, 3}));
  EXPECT_EQ(out.classes.size(), 5u);
  const auto label = [&](int x, int y) { return out.labels[out.geometry.index(x, y)]; };
  const auto occupancy = [&](int x, int y) { return out.occupancy[out.geometry.index(x, y)]; };
  EXPECT_EQ(label(40, 30), out.class_index("fence"));   // carried over by name
  EXPECT_EQ(label(0, 20), out.class_index("others"));   // labelled wall
  EXPECT_EQ(label(59, 20), out.class_index("others"));  // unlabelled wall: others
  EXPECT_EQ(label(10, 10), -1);                         // free space
  EXPECT_EQ(label(20, 12), out.class_index("door"));
  EXPECT_EQ(occupancy(20, 12), Occupancy::kOccupied);
  EXPECT_EQ(label(20, 15), out.class_index("glass_door"));  // painted last
  EXPECT_EQ(occupancy(20, 15), Occupancy::kFree);
  EXPECT_EQ(label(25, 15), out.class_index("glass_door"));
  EXPECT_EQ(label(30, 0), out.class_index("no_entry_line"));
  EXPECT_EQ(occupancy(30, 0), Occupancy::kOccupied);  // kept: the wall it crosses
  EXPECT_EQ(occupancy(30, 20), Occupancy::kFree);
  EXPECT_EQ(summary.cells_per_object, (std::vector<int64_t>{10, 40, 6}));
  EXPECT_EQ(summary.occupancy_changed, 10 + 1);  // the door closed, one of its cells opened again
}

TEST(AnnotateMap, TheWrittenMapLoadsAsPaintedWithItsGeometry) {
  TempDir dir;
  SemanticMap map = walled_map();
  map.geometry.resolution = 0.025;
  map.geometry.origin = {-12.345678, 3.5, 0.25};
  for (int x = 10; x < 20; ++x) {
    map.occupancy[map.geometry.index(x, 5)] = Occupancy::kUnknown;
  }
  const Pose2 o = map.geometry.origin;
  const auto world = [&](double gx, double gy) { return transform_point(o, Eigen::Vector2d(gx, gy) * 0.025); };
  ObjectList list;
  list.classes = project_classes();
  list.objects.push_back(line({world(5.5, 20.5), world(5.5, 30.5)}));
  list.objects.push_back(polygon({world(30, 10), world(40, 10), world(40, 20)}));
  list.objects.back().class_name = "fence";
  const SemanticMap painted = annotate_map(map, list);
  write_semantic_map(painted, dir.path.string(), "a test");
  const SemanticMap loaded = load_semantic_map(dir.file("map.yaml"));
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(loaded.unknown_color_cells, 0);
  EXPECT_EQ(loaded.geometry.width, 60);
  EXPECT_EQ(loaded.geometry.height, 40);
  EXPECT_DOUBLE_EQ(loaded.geometry.resolution, 0.025);
  EXPECT_NEAR(loaded.geometry.origin.x, -12.345678, 1e-12);
  EXPECT_NEAR(loaded.geometry.origin.theta, 0.25, 1e-12);
  ASSERT_EQ(loaded.classes.size(), 5u);
  EXPECT_TRUE(loaded.occupancy == painted.occupancy);
  EXPECT_TRUE(loaded.labels == painted.labels);
  EXPECT_EQ(std::count(loaded.labels.begin(), loaded.labels.end(), loaded.class_index("door")), 11);
  EXPECT_EQ(loaded.occupancy[loaded.geometry.index(12, 5)], Occupancy::kUnknown);
  // The preview: scaled by a whole factor, the door in its colour, tinted where it is free.
  const cv::Mat preview = render_preview(painted, list);
  const int legend = kPreviewLegendTop + 5 * kPreviewLegendRow;
  EXPECT_EQ(preview.cols, 60 * 8);
  EXPECT_EQ(preview.rows, legend + 40 * 8 + 24);
  const cv::Vec3b door = preview.at<cv::Vec3b>(legend + (40 - 1 - 25) * 8 + 4, 5 * 8 + 4);
  EXPECT_EQ(preview.at<cv::Vec3b>(legend + (40 - 1 - 10) * 8 + 4, 10 * 8 + 4), cv::Vec3b(255, 255, 255));  // free
  EXPECT_EQ(door, cv::Vec3b(255, 170, 255));  // (255, 0, 255) two thirds of the way to white
}

// Two rooms with a doorway at x = 3 m, y 1.5..2.5 m, as a SLAM package would map them (no classes).
SemanticMap two_rooms() {
  SemanticMap map = walled_map();
  for (int y = 0; y < 40; ++y) {
    if (y < 15 || y >= 25) {
      map.occupancy[map.geometry.index(30, y)] = Occupancy::kOccupied;
    }
  }
  return map;
}

// The localizer takes the painted classes: its node starts on the annotated map
// only, and the SLAMER term (Eqs. (7)-(9)) tells where the recognized door is.
TEST(AnnotateMap, TheLocalizerUsesThePaintedClasses) {
  TempDir dir;
  const SemanticMap slam = two_rooms();
  const ObjectList list = objects("objects:\n  - {class: door, line: [3.05, 1.5, 3.05, 2.5]}\n", slam);
  write_semantic_map(annotate_map(slam, list), dir.path.string(), "a test");
  const SemanticMap annotated = load_semantic_map(dir.file("map.yaml"));

  LocalizerOptions options;
  options.particles = 20;
  options.initial_pose = {1.5, 2.0, 0.0};
  EXPECT_NO_THROW(LocalizerNode(annotated, options, Pose2{}));
  EXPECT_THROW(LocalizerNode(slam, options, Pose2{}), ConfigError);  // no door class to map open_door to

  // An open door recognized 1.55 m ahead of a robot at (1.5, 2.0) facing +x.
  const std::vector<std::string> classes = paper_recognition_classes();
  LineObject door;
  door.kind = LineKind::kSpatial;
  door.start = {1.55, -0.5};
  door.end = {1.55, 0.5};
  door.probs = std::vector<float>(classes.size(), 0.02f);
  door.probs[0] = 0.86f;  // open_door
  const auto discrimination = [&](const SemanticMap& map) {
    const ParticleFilter filter(map, options, Pose2{});
    return filter.object_log_likelihood({1.5, 2.0, 0.0}, door, classes) -
           filter.object_log_likelihood({1.5, 2.8, 0.0}, door, classes);
  };
  const double with_classes = discrimination(annotated);
  EXPECT_GT(with_classes, 1.0);
  EXPECT_GT(with_classes, discrimination(slam) + 1.0);
}

}  // namespace
}  // namespace slamer

// slamer-annotate-map as a program: the shipped example paints the small room's
// semantic layer onto its bare map_server map where the bundled map has it, the
// output loads without a warning, and a bad objects file or output folder is
// one line and a non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "common/map/semantic_map.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBinary = SLAMER_BINARY_DIR;
const std::string kExamples = kSource + "/config/maps/examples/";

int run(const std::vector<std::string>& args, std::string* out, std::string* err) {
  test::ChildProcess child(test::binary_path("slamer-annotate-map"), args);
  const std::optional<int> code = child.wait(30.0);
  *out = child.stdout_text();
  *err = child.stderr_text();
  EXPECT_TRUE(code.has_value()) << "slamer-annotate-map did not finish";
  return code.value_or(-1);
}

// Cells of `name` in `a` and not within one cell of a cell of `name` in `b`.
int unmatched(const SemanticMap& a, const SemanticMap& b, const std::string& name) {
  const int la = a.class_index(name);
  const int lb = b.class_index(name);
  int count = 0;
  for (int y = 0; y < a.geometry.height; ++y) {
    for (int x = 0; x < a.geometry.width; ++x) {
      if (a.labels[a.geometry.index(x, y)] != la) {
        continue;
      }
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy) {
        for (int dx = -1; dx <= 1 && !near; ++dx) {
          near = b.geometry.contains(x + dx, y + dy) && b.labels[b.geometry.index(x + dx, y + dy)] == lb;
        }
      }
      count += near ? 0 : 1;
    }
  }
  return count;
}

TEST(SlamerAnnotateMap, TheExamplePaintsTheSmallRoomAsItsPlanDoes) {
  const std::string out_dir = kBinary + "/annotate_example";
  std::filesystem::remove_all(out_dir);
  std::string out;
  std::string err;
  ASSERT_EQ(run({kExamples + "small_room_slam.yaml", kExamples + "objects_example.yaml", out_dir}, &out, &err), 0)
      << err;
  EXPECT_EQ(err, "");
  EXPECT_NE(out.find("door: 1 object(s), 40 cells\n"), std::string::npos) << out;
  EXPECT_NE(out.find("wrote " + out_dir + "/map.yaml"), std::string::npos) << out;
  const SemanticMap annotated = load_semantic_map(out_dir + "/map.yaml");
  EXPECT_TRUE(annotated.warnings.empty());
  EXPECT_EQ(annotated.unknown_color_cells, 0);
  const SemanticMap bundled = load_semantic_map(kSource + "/config/maps/small_room/map.yaml");
  ASSERT_EQ(annotated.geometry.width, bundled.geometry.width);
  ASSERT_EQ(annotated.geometry.height, bundled.geometry.height);
  for (const std::string name : {"door", "glass_door", "fence", "no_entry_line"}) {
    const auto count = [](const SemanticMap& m, const std::string& c) {
      return std::count(m.labels.begin(), m.labels.end(), m.class_index(c));
    };
    EXPECT_GT(count(annotated, name), 20) << name;
    // The same cells as the plan's, give or take a cell where a stroke's edge falls on a cell's centre.
    EXPECT_EQ(unmatched(annotated, bundled, name), 0) << name;
    EXPECT_EQ(unmatched(bundled, annotated, name), 0) << name;
  }
  // The cabinet is occupied others where the bundled map has free space.
  const auto cabinet = annotated.geometry.cell_at({3.3, 4.5});
  ASSERT_TRUE(cabinet);
  const std::size_t i = annotated.geometry.index(cabinet->x, cabinet->y);
  EXPECT_EQ(annotated.occupancy[i], Occupancy::kOccupied);
  EXPECT_EQ(bundled.occupancy[i], Occupancy::kFree);
  EXPECT_EQ(annotated.labels[i], annotated.class_index("others"));
  const cv::Mat preview = cv::imread(out_dir + "/preview.png");
  EXPECT_EQ(preview.cols, annotated.geometry.width * 5);
  EXPECT_GT(preview.rows, annotated.geometry.height * 5);  // and the legend
}

TEST(SlamerAnnotateMap, BadInputIsOneLineAndExitCodeOne) {
  const std::string objects = kBinary + "/annotate_bad_objects.yaml";
  std::ofstream(objects) << "objects:\n  - {name: side door, class: dor, line: [6.0, 2.5, 6.0, 3.5]}\n";
  std::string out;
  std::string err;
  EXPECT_EQ(run({kExamples + "small_room_slam.yaml", objects, kBinary + "/annotate_bad"}, &out, &err), 1);
  EXPECT_EQ(err, "slamer-annotate-map: config error: " + objects +
                     ":2: key 'objects[0].class': object 'side door': unknown class 'dor' (the classes: door, "
                     "glass_door, fence, no_entry_line, others; add others under 'classes:')\n");
  EXPECT_FALSE(std::filesystem::exists(kBinary + "/annotate_bad"));  // nothing written
  EXPECT_EQ(run({kBinary + "/no_such_map.yaml", objects, kBinary + "/annotate_bad"}, &out, &err), 1);
  EXPECT_EQ(err, "slamer-annotate-map: config error: " + kBinary +
                     "/no_such_map.yaml: cannot open: No such file or "
                     "directory\n");
  // Into the map's own folder: refused before anything is written.
  EXPECT_EQ(run({kExamples + "small_room_slam.yaml", kExamples + "objects_example.yaml", kExamples}, &out, &err), 2);
  EXPECT_NE(err.find("is the folder of"), std::string::npos) << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_EQ(run({kExamples + "small_room_slam.yaml"}, &out, &err), 2);
  std::remove(objects.c_str());
}

}  // namespace
}  // namespace slamer

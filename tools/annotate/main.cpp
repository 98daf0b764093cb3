// slamer-annotate-map MAP.yaml OBJECTS.yaml OUT_DIR: the semantic layer for a
// map a SLAM package made (annotate.hpp, object_list.hpp).
#include <filesystem>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "tools/annotate/annotate.hpp"

namespace slamer {
namespace {

constexpr const char* kProgram = "slamer-annotate-map";

int run(const CommandLine& cli) {
  const std::string map_path = cli.positional()[0];
  const std::string objects_path = cli.positional()[1];
  const std::filesystem::path out = cli.positional()[2];
  const SemanticMap map = load_semantic_map(map_path);
  for (const std::string& warning : map.warnings) {
    log_line(kProgram, LogLevel::kWarning, warning);
  }
  std::error_code error;
  const auto map_dir = std::filesystem::weakly_canonical(std::filesystem::absolute(map_path).parent_path(), error);
  if (std::filesystem::weakly_canonical(std::filesystem::absolute(out), error) == map_dir) {
    throw CommandLineError("OUT_DIR '" + out.string() + "' is the folder of " + map_path +
                           ": write the annotated map into another one, so the input stays as it is");
  }
  const ObjectList list = load_object_list(objects_path, map);
  AnnotationSummary summary;
  const SemanticMap annotated = annotate_map(map, list, &summary);
  std::filesystem::create_directories(out, error);
  if (error) {
    throw std::runtime_error("cannot create " + out.string() + ": " + error.message());
  }
  write_semantic_map(
      annotated, out.string(),
      "Written by slamer-annotate-map from " + map_path + " and " + objects_path + "; edit those and run it again.");
  const std::string preview = (out / "preview.png").string();
  if (!cv::imwrite(preview, render_preview(annotated, list))) {
    throw std::runtime_error("cannot write " + preview);
  }
  std::map<std::string, std::pair<int, int64_t>> per_class;  // objects, cells
  for (std::size_t k = 0; k < list.objects.size(); ++k) {
    auto& [objects, cells] = per_class[list.objects[k].class_name];
    ++objects;
    cells += summary.cells_per_object[k];
  }
  for (const auto& [name, counts] : per_class) {
    std::cout << name << ": " << counts.first << " object(s), " << counts.second << " cells\n";
  }
  std::cout << summary.occupancy_changed << " cells changed occupancy\n"
            << "wrote " << (out / "map.yaml").string() << " (map.pgm, semantic.png) and " << preview
            << "; localize on it with: slamer-localizer --map " << (out / "map.yaml").string() << "\n";
  return 0;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, slamer::kProgram,
      "Paints classed lines and polygons (doors, glass doors, fences, no-entry lines, ...; OBJECTS.yaml, in\n"
      "map coordinates [m]) onto a map_server map (MAP.yaml from gmapping, slam_toolbox, cartographer, ...)\n"
      "and writes the semantic map slamer-localizer --map loads into OUT_DIR: map.yaml, map.pgm,\n"
      "semantic.png, and preview.png to check by eye. See config/maps/examples/objects_example.yaml.",
      [](slamer::CommandLine& cli) {
        cli.set_positional("MAP.yaml OBJECTS.yaml OUT_DIR", "the map, the objects and the output folder", 3, 3);
      },
      slamer::run);
}

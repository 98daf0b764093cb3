#include "common/map/semantic_map.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <utility>

#include "common/config/config_reader.hpp"

namespace slamer {
namespace {

constexpr std::array<uint8_t, 3> kIsmUnknown{205, 205, 205};
constexpr std::array<uint8_t, 3> kIsmFree{254, 254, 254};
constexpr std::string_view kIsmNoEntry = "do_not_enter_line";  // ism.yaml's name for...
constexpr std::string_view kNoEntry = "no_entry_line";         // ...this project's class

// For a binary PGM/PPM (P5/P6): what is wrong with its header or size, or ""
// (also for other formats, which OpenCV checks).
std::string binary_netpbm_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  in >> magic;
  if (magic != "P5" && magic != "P6") {
    return "";
  }
  long long fields[3] = {};  // width, height, maxval; '#' comments may come between them
  // Bounds keep the size below from overflowing: 2^20 pixels a side (52 km at
  // 5 cm) and the format's own maxval limit.
  const long long limits[3] = {1LL << 20, 1LL << 20, 65535};
  for (int i = 0; i < 3; ++i) {
    while (in >> std::ws && in.peek() == '#') {
      std::string comment;
      std::getline(in, comment);
    }
    if (!(in >> fields[i]) || fields[i] <= 0 || fields[i] > limits[i]) {
      return "has a damaged header";
    }
  }
  in.get();  // the one whitespace byte before the pixels
  const long long channels = magic == "P6" ? 3 : 1;
  const long long expected = fields[0] * fields[1] * channels * (fields[2] > 255 ? 2 : 1);
  const long long start = static_cast<long long>(in.tellg());
  in.seekg(0, std::ios::end);
  const long long size = static_cast<long long>(in.tellg());
  if (start < 0 || size - start < expected) {
    return "is cut short: " + std::to_string(fields[0]) + " x " + std::to_string(fields[1]) + " pixels need " +
           std::to_string(expected) + " bytes, the file has " + std::to_string(std::max(0LL, size - start));
  }
  return "";
}

cv::Mat read_image(const ConfigReader& reader, std::string_view key, const std::string& path) {
  if (path.empty()) {
    reader.fail(key, "missing (this key is required)");
  }
  const std::string full = reader.resolve_path(path);
  std::error_code error;
  if (!std::filesystem::is_regular_file(full, error)) {
    reader.fail(key, "image '" + full + "' does not exist");
  }
  // Only the map_server formats reach OpenCV, whatever the file is named:
  // imread sniffs the content and would hand other bytes to a dozen decoders.
  char magic[8] = {};
  std::ifstream(full, std::ios::binary).read(magic, sizeof(magic));
  const bool png = std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool netpbm = magic[0] == 'P' && (magic[1] == '2' || magic[1] == '3' || magic[1] == '5' || magic[1] == '6');
  if (!png && !netpbm) {
    reader.fail(key, "image '" + full + "' is not a PGM/PPM or PNG file");
  }
  if (const std::string problem = binary_netpbm_problem(full); !problem.empty()) {
    reader.fail(key, "image '" + full + "' " + problem);  // before OpenCV, which would print lines of its own
  }
  cv::Mat image;
  try {
    image = cv::imread(full, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image = cv::Mat();
  }
  if (image.empty()) {
    reader.fail(key, "cannot decode image '" + full + "' (not a PGM/PNG OpenCV can read?)");
  }
  if (image.depth() != CV_8U) {
    reader.fail(key,
                "image '" + full + "' has " + std::to_string(image.elemSize1() * 8) + "-bit channels; 8-bit expected");
  }
  return image;
}

struct MapServerFile {
  std::string image;
  double resolution = 0.0;
  std::vector<double> origin;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  bool negate = false;
  std::string mode = "trinary";
};

// Reads the map_server keys of `reader` and fills geometry and occupancy.
void read_map_server(const ConfigReader& reader, MapServerFile* file, SemanticMap* map) {
  reader.require("image");
  reader.require("resolution");
  reader.require("origin");
  reader.read("image", &file->image);
  reader.read("resolution", &file->resolution, positive());
  reader.read("origin", &file->origin, {}, 3);
  reader.read("occupied_thresh", &file->occupied_thresh, probability());
  reader.read("free_thresh", &file->free_thresh, probability());
  std::string negate = "0";  // map_server writes 0/1; true/false are accepted too
  reader.read_choice("negate", &negate, {"0", "1", "false", "true"});
  file->negate = negate == "1" || negate == "true";
  reader.read_choice("mode", &file->mode, {"trinary", "scale", "raw"});
  if (file->free_thresh > file->occupied_thresh) {
    reader.fail("free_thresh", "must not exceed occupied_thresh (" + std::to_string(file->occupied_thresh) + ")");
  }
  const cv::Mat image = read_image(reader, "image", file->image);
  map->geometry.width = image.cols;
  map->geometry.height = image.rows;
  map->geometry.resolution = file->resolution;
  map->geometry.origin = {file->origin[0], file->origin[1], wrap_angle(file->origin[2])};
  map->occupancy.assign(map->geometry.size(), Occupancy::kUnknown);
  const int channels = image.channels();
  for (int row = 0; row < image.rows; ++row) {
    const uint8_t* pixel = image.ptr<uint8_t>(row);
    for (int col = 0; col < image.cols; ++col, pixel += channels) {
      // map_server: mean of the colour channels; alpha 0 means unknown.
      const int colour_channels = channels == 4 ? 3 : channels == 2 ? 1 : channels;
      double sum = 0.0;
      for (int c = 0; c < colour_channels; ++c) {
        sum += pixel[c];
      }
      if ((channels == 4 && pixel[3] == 0) || (channels == 2 && pixel[1] == 0)) {
        continue;
      }
      const double mean = sum / colour_channels;
      const double occupied_probability = file->negate ? mean / 255.0 : (255.0 - mean) / 255.0;
      // "raw" images hold occupancy in percent (0 free .. 100 occupied, above that unknown).
      const double probability = file->mode == "raw" ? (mean <= 100.0 ? mean / 100.0 : -1.0) : occupied_probability;
      Occupancy cell = Occupancy::kUnknown;
      if (probability < 0.0) {
        cell = Occupancy::kUnknown;
      } else if (probability > file->occupied_thresh) {
        cell = Occupancy::kOccupied;
      } else if (probability < file->free_thresh) {
        cell = Occupancy::kFree;
      }
      map->occupancy[map->geometry.index(col, image.rows - 1 - row)] = cell;
    }
  }
}

std::array<uint8_t, 3> read_color(const ConfigReader& reader, std::string_view key) {
  std::vector<double> rgb;
  reader.require(key);
  reader.read(key, &rgb, in_range(0, 255), 3);
  for (const double c : rgb) {
    if (c != static_cast<int>(c)) {
      reader.fail(key, "colour components must be integers in [0, 255]");
    }
  }
  return {static_cast<uint8_t>(rgb[0]), static_cast<uint8_t>(rgb[1]), static_cast<uint8_t>(rgb[2])};
}

void check_classes(const ConfigReader& reader, std::string_view key, const std::vector<SemanticClass>& classes) {
  if (classes.size() > 127) {
    reader.fail(key, "at most 127 classes are supported");
  }
  for (std::size_t i = 0; i < classes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (classes[i].name == classes[j].name) {
        reader.fail(key, "class '" + classes[i].name + "' is listed twice");
      }
      if (classes[i].rgb == classes[j].rgb) {
        reader.fail(key, "classes '" + classes[j].name + "' and '" + classes[i].name + "' share a colour");
      }
    }
    if (classes[i].rgb == kIsmUnknown || classes[i].rgb == kIsmFree) {
      reader.fail(key, "class '" + classes[i].name + "' uses a colour reserved for unknown/free space");
    }
  }
}

// Labels cells from a colour image of the map's size; `ignored` colours carry no label.
void read_labels(const ConfigReader& reader, std::string_view key, const std::string& path,
                 const std::vector<std::array<uint8_t, 3>>& ignored, SemanticMap* map) {
  const cv::Mat image = read_image(reader, key, path);
  if (image.cols != map->geometry.width || image.rows != map->geometry.height) {
    reader.fail(key, "semantic image is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                         " but the occupancy image is " + std::to_string(map->geometry.width) + "x" +
                         std::to_string(map->geometry.height));
  }
  if (image.channels() != 3 && image.channels() != 4) {
    reader.fail(
        key, "semantic image must be a colour image (RGB), it has " + std::to_string(image.channels()) + " channel(s)");
  }
  std::map<std::array<uint8_t, 3>, int8_t> lookup;
  for (std::size_t i = 0; i < map->classes.size(); ++i) {
    lookup[map->classes[i].rgb] = static_cast<int8_t>(i);
  }
  std::map<std::array<uint8_t, 3>, int64_t> unknown_colors;
  const int channels = image.channels();
  for (int row = 0; row < image.rows; ++row) {
    const uint8_t* pixel = image.ptr<uint8_t>(row);
    for (int col = 0; col < image.cols; ++col, pixel += channels) {
      const std::array<uint8_t, 3> rgb{pixel[2], pixel[1], pixel[0]};  // OpenCV stores BGR
      const auto it = lookup.find(rgb);
      if (it != lookup.end()) {
        map->labels[map->geometry.index(col, image.rows - 1 - row)] = it->second;
      } else if (std::find(ignored.begin(), ignored.end(), rgb) == ignored.end()) {
        ++unknown_colors[rgb];
        ++map->unknown_color_cells;
      }
    }
  }
  if (!unknown_colors.empty()) {
    const auto& [rgb, count] = *std::max_element(unknown_colors.begin(), unknown_colors.end(),
                                                 [](const auto& a, const auto& b) { return a.second < b.second; });
    map->warnings.push_back(reader.source() + ": " + std::to_string(map->unknown_color_cells) + " semantic pixels in " +
                            std::to_string(unknown_colors.size()) + " colour(s) of no class (most: [" +
                            std::to_string(rgb[0]) + ", " + std::to_string(rgb[1]) + ", " + std::to_string(rgb[2]) +
                            "] x " + std::to_string(count) + "); they are left unlabelled");
  }
}

void label_unlabelled_occupied(const std::string& occupied_class, SemanticMap* map) {
  const int index = map->class_index(occupied_class);
  if (index < 0) {
    return;
  }
  for (std::size_t i = 0; i < map->labels.size(); ++i) {
    if (map->labels[i] < 0 && map->occupancy[i] == Occupancy::kOccupied) {
      map->labels[i] = static_cast<int8_t>(index);
    }
  }
}

SemanticMap load_ism(const ConfigReader& reader) {
  SemanticMap map;
  std::string ogm_yaml;
  std::string image;
  std::vector<std::string> objects;
  reader.read("ogm_info_yaml", &ogm_yaml);
  reader.require("image");
  reader.read("image", &image);
  reader.require("objects");
  reader.read("objects", &objects);
  if (std::find(objects.begin(), objects.end(), kIsmNoEntry) != objects.end() &&
      std::find(objects.begin(), objects.end(), kNoEntry) != objects.end()) {
    reader.fail("objects", "lists both do_not_enter_line and no_entry_line, which are one class here");
  }
  for (const std::string& name : objects) {
    map.classes.push_back({name == kIsmNoEntry ? std::string(kNoEntry) : name, read_color(reader, name + "_color")});
  }
  check_classes(reader, "objects", map.classes);
  reader.check_all_keys_used();

  const ConfigReader ogm = ConfigReader::from_file(reader.resolve_path(ogm_yaml));
  MapServerFile file;
  read_map_server(ogm, &file, &map);
  ogm.check_all_keys_used();
  map.labels.assign(map.geometry.size(), -1);
  read_labels(reader, "image", image, {kIsmUnknown, kIsmFree}, &map);
  label_unlabelled_occupied("others", &map);
  return map;
}

SemanticMap load_map_server(const ConfigReader& reader) {
  SemanticMap map;
  MapServerFile file;
  read_map_server(reader, &file, &map);
  map.labels.assign(map.geometry.size(), -1);
  if (reader.has("semantic")) {
    const ConfigReader semantic = reader.section("semantic");
    std::string image;
    semantic.require("image");
    semantic.read("image", &image);
    for (const ConfigReader& entry : semantic.list("classes")) {
      SemanticClass c;
      entry.require("name");
      entry.read("name", &c.name);
      c.rgb = read_color(entry, "color");
      map.classes.push_back(c);
    }
    if (map.classes.empty()) {
      semantic.fail("classes", "the class table is empty");
    }
    check_classes(semantic, "classes", map.classes);
    std::string occupied_class = map.class_index("others") >= 0 ? "others" : "";
    semantic.read("occupied_class", &occupied_class);
    if (!occupied_class.empty() && map.class_index(occupied_class) < 0) {
      semantic.fail("occupied_class", "'" + occupied_class + "' is not in the class table");
    }
    read_labels(semantic, "image", image, {kIsmUnknown, kIsmFree, {255, 255, 255}}, &map);
    label_unlabelled_occupied(occupied_class, &map);
  }
  reader.check_all_keys_used();
  return map;
}

}  // namespace

int SemanticMap::class_index(std::string_view name) const {
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i].name == name) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

SemanticMap load_semantic_map(const std::string& yaml_path) {
  const ConfigReader reader = ConfigReader::from_file(yaml_path);
  return reader.has("ogm_info_yaml") ? load_ism(reader) : load_map_server(reader);
}

namespace {

// A distance field over the cells where `is_target(cell index)` holds, built
// row by row so that no full-size mask is ever allocated.
template <typename Predicate>
DistanceField field_of(const SemanticMap& map, double max_distance, Predicate is_target) {
  return {map.geometry,
          [&](int y, uint8_t* row) {
            const std::size_t first = map.geometry.index(0, y);
            for (int x = 0; x < map.geometry.width; ++x) {
              row[x] = is_target(first + static_cast<std::size_t>(x)) ? 1 : 0;
            }
          },
          max_distance};
}

}  // namespace

DistanceField obstacle_distance_field(const SemanticMap& map, double max_distance) {
  return field_of(map, max_distance, [&](std::size_t i) { return map.occupancy[i] == Occupancy::kOccupied; });
}

std::vector<DistanceField> class_distance_fields(const SemanticMap& map, double max_distance) {
  std::vector<DistanceField> fields;
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    const auto label = static_cast<int8_t>(c);
    fields.push_back(field_of(map, max_distance, [&](std::size_t i) { return map.labels[i] == label; }));
  }
  return fields;
}

DistanceField free_space_distance_field(const SemanticMap& map, double max_distance, double class_margin,
                                        const std::vector<double>& class_margins) {
  const auto free_of_class = [&](std::size_t i) { return map.occupancy[i] == Occupancy::kFree && map.labels[i] < 0; };
  const auto margin_of = [&](std::size_t c) {
    return c < class_margins.size() && class_margins[c] > 0.0 ? class_margins[c] : class_margin;
  };
  // One field for the classes at the common margin, one for each class with a margin of its own;
  // each reaches a step beyond its margin so that "more than the margin" is not lost to its levels.
  std::vector<std::pair<DistanceField, double>> to_classes;
  const auto add = [&](double margin, const std::function<bool(int8_t)>& counts) {
    if (margin > 0.0) {
      to_classes.emplace_back(field_of(map, margin + map.geometry.resolution,
                                       [&](std::size_t i) { return map.labels[i] >= 0 && counts(map.labels[i]); }),
                              margin);
    }
  };
  add(class_margin, [&](int8_t label) { return margin_of(static_cast<std::size_t>(label)) == class_margin; });
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    if (margin_of(c) != class_margin) {
      add(margin_of(c), [&](int8_t label) { return static_cast<std::size_t>(label) == c; });
    }
  }
  if (to_classes.empty()) {
    return field_of(map, max_distance, free_of_class);
  }
  const auto width = static_cast<std::size_t>(map.geometry.width);
  return field_of(map, max_distance, [&](std::size_t i) {
    const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
    return free_of_class(i) && std::all_of(to_classes.begin(), to_classes.end(),
                                           [&](const auto& field) { return field.first.at(x, y) > field.second; });
  });
}

}  // namespace slamer

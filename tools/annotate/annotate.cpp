#include "tools/annotate/annotate.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tools/annotate/object_cells.hpp"

namespace slamer {
namespace {

constexpr uint8_t kFreeGrey = 254;
constexpr uint8_t kUnknownGrey = 205;
constexpr int kPreviewBottom = 24;  // [px] the scale bar's band

cv::Vec3b bgr(const std::array<uint8_t, 3>& rgb) {
  return {rgb[2], rgb[1], rgb[0]};
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.12g", value);
  return text;
}

// A class name as a YAML scalar: plain if it is a plain word, else single-quoted (a map's own names may be anything).
std::string yaml_string(const std::string& name) {
  const bool plain =
      !name.empty() && std::isalpha(static_cast<unsigned char>(name[0])) &&
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") == std::string::npos;
  if (plain) {
    return name;
  }
  std::string quoted = "'";
  for (const char ch : name) {
    quoted += ch == '\'' ? "''" : std::string(1, ch);
  }
  return quoted + "'";
}

}  // namespace

SemanticMap annotate_map(const SemanticMap& map, const ObjectList& list, AnnotationSummary* summary) {
  SemanticMap out;
  out.geometry = map.geometry;
  out.occupancy = map.occupancy;
  out.classes = list.classes;
  out.labels.assign(map.geometry.size(), -1);
  std::vector<int8_t> relabel(map.classes.size(), -1);
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    relabel[c] = static_cast<int8_t>(out.class_index(map.classes[c].name));
  }
  const auto others = static_cast<int8_t>(out.class_index("others"));
  for (std::size_t i = 0; i < out.labels.size(); ++i) {
    const int8_t old = map.labels.empty() ? int8_t{-1} : map.labels[i];
    out.labels[i] = old >= 0 ? relabel[static_cast<std::size_t>(old)] : int8_t{-1};
    if (out.labels[i] < 0 && out.occupancy[i] == Occupancy::kOccupied) {
      out.labels[i] = others;
    }
  }
  AnnotationSummary counts;
  for (const MapObject& object : list.objects) {
    const auto label = static_cast<int8_t>(out.class_index(object.class_name));
    if (label < 0) {
      throw std::invalid_argument("class '" + object.class_name + "' is not in the object list's class table");
    }
    const std::vector<std::size_t> cells = object_cells(object, out.geometry);
    for (const std::size_t i : cells) {
      out.labels[i] = label;
      const Occupancy set = object.occupancy == CellOccupancy::kOccupied ? Occupancy::kOccupied
                            : object.occupancy == CellOccupancy::kFree   ? Occupancy::kFree
                                                                         : out.occupancy[i];
      counts.occupancy_changed += set != out.occupancy[i] ? 1 : 0;
      out.occupancy[i] = set;
    }
    counts.cells_per_object.push_back(static_cast<int64_t>(cells.size()));
  }
  if (summary != nullptr) {
    *summary = counts;
  }
  return out;
}

void write_semantic_map(const SemanticMap& map, const std::string& directory, const std::string& header) {
  const GridGeometry& g = map.geometry;
  cv::Mat occupancy(g.height, g.width, CV_8UC1);
  cv::Mat semantic(g.height, g.width, CV_8UC3);
  for (int y = 0; y < g.height; ++y) {
    const int row = g.height - 1 - y;  // image row 0 is the top
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = g.index(x, y);
      const uint8_t grey = map.occupancy[i] == Occupancy::kOccupied ? 0
                           : map.occupancy[i] == Occupancy::kFree   ? kFreeGrey
                                                                    : kUnknownGrey;
      occupancy.at<uint8_t>(row, x) = grey;
      const int8_t label = map.labels[i];
      const uint8_t none = grey == 0 ? kUnknownGrey : grey;  // a colour of no class (occupied cells all have one)
      semantic.at<cv::Vec3b>(row, x) =
          label >= 0 ? bgr(map.classes[static_cast<std::size_t>(label)].rgb) : cv::Vec3b(none, none, none);
    }
  }
  const std::vector<int> png_options{cv::IMWRITE_PNG_COMPRESSION, 9};
  if (!cv::imwrite(directory + "/map.pgm", occupancy) ||
      !cv::imwrite(directory + "/semantic.png", semantic, png_options)) {
    throw std::runtime_error("cannot write the map images into " + directory);
  }
  std::ofstream yaml(directory + "/map.yaml");
  yaml << "# " << header << "\nimage: map.pgm\nresolution: " << number(g.resolution) << "\norigin: ["
       << number(g.origin.x) << ", " << number(g.origin.y) << ", " << number(g.origin.theta)
       << "]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nsemantic:\n  image: semantic.png\n  classes:\n";
  for (const SemanticClass& c : map.classes) {
    yaml << "    - {name: " << yaml_string(c.name) << ", color: [" << int{c.rgb[0]} << ", " << int{c.rgb[1]} << ", "
         << int{c.rgb[2]} << "]}\n";
  }
  if (!yaml) {
    throw std::runtime_error("cannot write " + directory + "/map.yaml");
  }
}

cv::Mat render_preview(const SemanticMap& map, const ObjectList& list) {
  const GridGeometry& g = map.geometry;
  const int scale = std::clamp(1200 / std::max({g.width, g.height, 1}), 1, 8);
  cv::Mat cells(g.height, g.width, CV_8UC3);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = g.index(x, y);
      cv::Vec3b colour = map.occupancy[i] == Occupancy::kFree      ? cv::Vec3b(255, 255, 255)
                         : map.occupancy[i] == Occupancy::kUnknown ? cv::Vec3b(190, 190, 190)
                                                                   : cv::Vec3b(0, 0, 0);
      if (map.labels[i] >= 0) {
        colour = bgr(map.classes[static_cast<std::size_t>(map.labels[i])].rgb);
        if (map.occupancy[i] != Occupancy::kOccupied) {  // open / passable: a tint
          for (int c = 0; c < 3; ++c) {
            colour[c] = static_cast<uint8_t>((colour[c] + 2 * 255) / 3);
          }
        }
      }
      cells.at<cv::Vec3b>(g.height - 1 - y, x) = colour;
    }
  }
  cv::Mat map_image;
  cv::resize(cells, map_image, cv::Size(g.width * scale, g.height * scale), 0, 0, cv::INTER_NEAREST);
  // The map between a legend band above and a scale bar band below, so neither hides a cell.
  const int legend = kPreviewLegendTop + kPreviewLegendRow * static_cast<int>(map.classes.size());
  cv::Mat image(legend + map_image.rows + kPreviewBottom, std::max(map_image.cols, 240), CV_8UC3,
                cv::Scalar(235, 235, 235));
  map_image.copyTo(image(cv::Rect(0, legend, map_image.cols, map_image.rows)));
  const auto text = [&](const std::string& s, cv::Point at) {
    cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(255, 255, 255), 3, cv::LINE_AA);
    cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  };
  for (std::size_t k = 0; k < list.objects.size(); ++k) {
    const Eigen::Vector2d p = g.to_grid(list.objects[k].points.front()) * scale;
    text(std::to_string(k),
         cv::Point(static_cast<int>(p.x()) + 4, legend + map_image.rows - static_cast<int>(p.y()) - 4));
  }
  // Legend: per class a swatch (occupied | free tint) and its name.
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    const int top = kPreviewLegendTop / 2 + kPreviewLegendRow * static_cast<int>(c);
    const cv::Vec3b solid = bgr(map.classes[c].rgb);
    const cv::Scalar tint((solid[0] + 510) / 3, (solid[1] + 510) / 3, (solid[2] + 510) / 3);
    cv::rectangle(image, cv::Rect(6, top, 12, 12), cv::Scalar(solid[0], solid[1], solid[2]), cv::FILLED);
    cv::rectangle(image, cv::Rect(18, top, 12, 12), tint, cv::FILLED);
    cv::rectangle(image, cv::Rect(6, top, 24, 12), cv::Scalar(40, 40, 40), 1);
    text(map.classes[c].name + (c == 0 ? "  (solid: occupied, light: free)" : ""), cv::Point(36, top + 11));
  }
  // 1 m scale bar.
  const int metre = static_cast<int>(std::lround(scale / g.resolution));
  const int bar = image.rows - kPreviewBottom / 2;
  cv::line(image, cv::Point(8, bar), cv::Point(8 + metre, bar), cv::Scalar(40, 40, 40), 2);
  text("1 m", cv::Point(14 + metre, bar + 4));
  return image;
}

}  // namespace slamer

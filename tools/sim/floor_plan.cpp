#include "tools/sim/floor_plan.hpp"

#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/geometry/polygon.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, FloorPlan* plan) {
  reader.read("resolution", &plan->resolution, positive());
  std::vector<double> size{plan->size.x(), plan->size.y()};
  reader.read("size", &size, positive(), 2);
  plan->size = {size[0], size[1]};
  std::vector<double> origin{plan->origin.x(), plan->origin.y()};
  reader.read("origin", &origin, {}, 2);
  plan->origin = {origin[0], origin[1]};
  reader.read("unknown_background", &plan->unknown_background);
  for (const ConfigReader& area : reader.list("free_areas")) {
    if (area.has("polygon")) {  // [x0, y0, x1, y1, ...], at least three corners
      std::vector<double> flat;
      area.read("polygon", &flat);
      if (flat.size() < 6 || flat.size() % 2 != 0) {
        area.fail("polygon", "expected a flat list x0, y0, x1, y1, ... of at least three corners");
      }
      std::vector<Eigen::Vector2d> polygon;
      for (std::size_t i = 0; i < flat.size(); i += 2) {
        polygon.emplace_back(flat[i], flat[i + 1]);
      }
      plan->free_polygons.push_back(polygon);
      continue;
    }
    std::vector<double> box;
    area.require("box");
    area.read("box", &box, {}, 4);
    plan->free_areas.push_back({box[0], box[1], box[2], box[3]});
  }
  for (const ConfigReader& entry : reader.list("classes")) {
    PlanClass c;
    entry.require("name");
    entry.read("name", &c.name);
    std::vector<double> rgb;
    entry.require("color");
    entry.read("color", &rgb, in_range(0, 255), 3);
    c.rgb = {static_cast<uint8_t>(rgb[0]), static_cast<uint8_t>(rgb[1]), static_cast<uint8_t>(rgb[2])};
    entry.read("occupied", &c.occupied);
    plan->classes.push_back(c);
  }
  for (const ConfigReader& entry : reader.list("shapes")) {
    PlanShape shape;
    entry.require("class");
    entry.read("class", &shape.class_name);
    const auto it = std::find_if(plan->classes.begin(), plan->classes.end(),
                                 [&](const PlanClass& c) { return c.name == shape.class_name; });
    if (it == plan->classes.end()) {
      entry.fail("class", "'" + shape.class_name + "' is not in classes");
    }
    shape.occupied = it->occupied;
    entry.read("occupied", &shape.occupied);
    entry.read("width", &shape.width, positive());
    std::vector<double> flat;
    entry.require("points");
    entry.read("points", &flat);  // [x0, y0, x1, y1, ...]
    if (flat.size() < 4 || flat.size() % 2 != 0) {
      entry.fail("points", "expected a flat list x0, y0, x1, y1, ... of at least two points");
    }
    for (std::size_t i = 0; i < flat.size(); i += 2) {
      shape.points.emplace_back(flat[i], flat[i + 1]);
    }
    plan->shapes.push_back(shape);
  }
}

void write_floor_plan_map(const FloorPlan& plan, const std::string& directory) {
  const int width = static_cast<int>(std::lround(plan.size.x() / plan.resolution));
  const int height = static_cast<int>(std::lround(plan.size.y() / plan.resolution));
  const uint8_t background = plan.unknown_background ? 205 : 254;
  cv::Mat occupancy(height, width, CV_8UC1, cv::Scalar(background));
  cv::Mat semantic(height, width, CV_8UC3, cv::Scalar(background, background, background));
  // World point of a pixel centre; image row 0 is the top.
  const auto center = [&](int col, int row) {
    return Eigen::Vector2d(plan.origin.x() + (col + 0.5) * plan.resolution,
                           plan.origin.y() + (height - 1 - row + 0.5) * plan.resolution);
  };
  for (const auto& box : plan.free_areas) {
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        const Eigen::Vector2d p = center(col, row);
        if (p.x() >= box[0] && p.x() <= box[2] && p.y() >= box[1] && p.y() <= box[3]) {
          occupancy.at<uint8_t>(row, col) = 254;
          semantic.at<cv::Vec3b>(row, col) = {254, 254, 254};
        }
      }
    }
  }
  for (const auto& polygon : plan.free_polygons) {
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        if (inside_polygon(center(col, row), polygon)) {
          occupancy.at<uint8_t>(row, col) = 254;
          semantic.at<cv::Vec3b>(row, col) = {254, 254, 254};
        }
      }
    }
  }
  for (const PlanShape& shape : plan.shapes) {
    const PlanClass& c = *std::find_if(plan.classes.begin(), plan.classes.end(),
                                       [&](const PlanClass& k) { return k.name == shape.class_name; });
    // At least half a cell, so a thin line is still a connected run of cells.
    const double half = std::max(shape.width, plan.resolution) / 2.0;
    for (std::size_t i = 0; i + 1 < shape.points.size(); ++i) {
      const Eigen::Vector2d& a = shape.points[i];
      const Eigen::Vector2d& b = shape.points[i + 1];
      const int col0 =
          std::max(0, static_cast<int>((std::min(a.x(), b.x()) - half - plan.origin.x()) / plan.resolution) - 1);
      const int col1 = std::min(
          width - 1, static_cast<int>((std::max(a.x(), b.x()) + half - plan.origin.x()) / plan.resolution) + 1);
      const int y0 = static_cast<int>((std::min(a.y(), b.y()) - half - plan.origin.y()) / plan.resolution) - 1;
      const int y1 = static_cast<int>((std::max(a.y(), b.y()) + half - plan.origin.y()) / plan.resolution) + 1;
      for (int gy = std::max(0, y0); gy <= std::min(height - 1, y1); ++gy) {
        const int row = height - 1 - gy;
        for (int col = col0; col <= col1; ++col) {
          if (distance_to_segment(center(col, row), a, b) <= half) {
            occupancy.at<uint8_t>(row, col) = shape.occupied ? 0 : 254;
            semantic.at<cv::Vec3b>(row, col) = {c.rgb[2], c.rgb[1], c.rgb[0]};
          }
        }
      }
    }
  }
  const std::vector<int> png_options{cv::IMWRITE_PNG_COMPRESSION, 9};
  if (!cv::imwrite(directory + "/map.pgm", occupancy) ||
      !cv::imwrite(directory + "/semantic.png", semantic, png_options)) {
    throw std::runtime_error("cannot write the map images into " + directory);
  }
  std::ofstream yaml(directory + "/map.yaml");
  yaml << "# Generated by slamer-make-map from plan.yaml; edit the plan, not this file.\n"
       << "image: map.pgm\nresolution: " << plan.resolution << "\norigin: [" << plan.origin.x() << ", "
       << plan.origin.y() << ", 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
       << "semantic:\n  image: semantic.png\n  classes:\n";
  for (const PlanClass& c : plan.classes) {
    yaml << "    - {name: " << c.name << ", color: [" << int{c.rgb[0]} << ", " << int{c.rgb[1]} << ", " << int{c.rgb[2]}
         << "]}\n";
  }
  if (!yaml) {
    throw std::runtime_error("cannot write " + directory + "/map.yaml");
  }
}

}  // namespace slamer

#include "tools/render/renderer.hpp"

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace slamer {
namespace {

cv::Scalar bgr(const cv::Scalar& rgb) {
  return {rgb[2], rgb[1], rgb[0]};
}

}  // namespace

FrameRenderer::FrameRenderer(const SemanticMap& map, RenderOptions options) : map_(map), options_(std::move(options)) {
  const GridGeometry& g = map.geometry;
  cv::Mat cells(g.height, g.width, CV_8UC3);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = g.index(x, y);
      cv::Vec3b colour = map.occupancy[i] == Occupancy::kFree       ? cv::Vec3b(255, 255, 255)
                         : map.occupancy[i] == Occupancy::kOccupied ? cv::Vec3b(60, 60, 60)
                                                                    : cv::Vec3b(200, 200, 200);
      if (map.labels[i] >= 0) {
        const auto& rgb = map.classes[static_cast<std::size_t>(map.labels[i])].rgb;
        // Faded class colour: the map is the backdrop, recognized objects are drawn over it.
        colour =
            cv::Vec3b(static_cast<uint8_t>(155 + rgb[2] * 100 / 255), static_cast<uint8_t>(155 + rgb[1] * 100 / 255),
                      static_cast<uint8_t>(155 + rgb[0] * 100 / 255));
        if (map.classes[static_cast<std::size_t>(map.labels[i])].name == "others") {
          colour = map.occupancy[i] == Occupancy::kOccupied ? cv::Vec3b(60, 60, 60) : cv::Vec3b(150, 150, 150);
        }
      }
      cells.at<cv::Vec3b>(g.height - 1 - y, x) = colour;
    }
  }
  cv::resize(cells, background_, cv::Size(), options_.pixels_per_cell, options_.pixels_per_cell, cv::INTER_NEAREST);
}

cv::Point FrameRenderer::to_pixel(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d g = map_.geometry.to_grid(world) * options_.pixels_per_cell;
  return {static_cast<int>(std::lround(g.x())), background_.rows - 1 - static_cast<int>(std::lround(g.y()))};
}

cv::Scalar FrameRenderer::color_of(const std::string& class_name) const {
  const auto it = options_.class_colors.find(class_name);
  return bgr(it == options_.class_colors.end() ? cv::Scalar(90, 90, 90) : it->second);
}

cv::Mat FrameRenderer::draw(const Frame& frame) const {
  cv::Mat image = background_.clone();
  const double scale = options_.pixels_per_cell / map_.geometry.resolution;  // pixels per metre
  const int thick = std::max(1, static_cast<int>(std::lround(0.06 * scale)));
  for (const Pose2& p : frame.particles) {
    cv::circle(image, to_pixel({p.x, p.y}), 1, cv::Scalar(255, 160, 80), cv::FILLED);
  }
  const std::optional<Pose2> view = frame.estimate ? frame.estimate : frame.truth;
  if (frame.scan && view) {
    const Pose2 sensor = compose(*view, options_.lidar_mount);
    for (std::size_t i = 0; i < frame.scan->ranges.size(); ++i) {
      const float r = frame.scan->ranges[i];
      if (!std::isfinite(r)) {
        continue;
      }
      const double a = frame.scan->angle(i);
      const Eigen::Vector2d p = transform_point(sensor, {r * std::cos(a), r * std::sin(a)});
      cv::circle(image, to_pixel(p), std::max(1, thick / 2), cv::Scalar(0, 0, 230), cv::FILLED);
    }
  }
  const auto draw_objects = [&](const LineObjectSet& set, const std::optional<Pose2>& frame_pose) {
    for (const LineObject& o : set.objects) {
      const int label = o.label >= 0 ? o.label : most_likely(o.probs);
      const std::string name =
          label >= 0 && static_cast<std::size_t>(label) < set.class_names.size() ? set.class_names[label] : "";
      const Eigen::Vector2d a = frame_pose ? transform_point(*frame_pose, o.start) : o.start;
      const Eigen::Vector2d b = frame_pose ? transform_point(*frame_pose, o.end) : o.end;
      cv::line(image, to_pixel(a), to_pixel(b), color_of(name), 2 * thick, cv::LINE_AA);
    }
  };
  if (frame.semantic) {
    draw_objects(*frame.semantic, std::nullopt);
  } else if (frame.recognized && view) {
    draw_objects(*frame.recognized, compose(*view, options_.lidar_mount));
  }
  const auto draw_pose = [&](const Pose2& p, const cv::Scalar& colour) {
    const cv::Point c = to_pixel({p.x, p.y});
    const int radius = std::max(3, static_cast<int>(std::lround(0.25 * scale)));
    cv::circle(image, c, radius, colour, thick, cv::LINE_AA);
    cv::line(image, c, to_pixel({p.x + 0.5 * std::cos(p.theta), p.y + 0.5 * std::sin(p.theta)}), colour, thick,
             cv::LINE_AA);
  };
  if (frame.truth) {
    draw_pose(*frame.truth, cv::Scalar(0, 170, 0));
  }
  if (frame.estimate) {
    draw_pose(*frame.estimate, cv::Scalar(220, 80, 0));
  }
  char label[96];
  std::snprintf(label, sizeof(label), "t = %.2f s   green: truth  blue: estimate  red dots: scan", frame.elapsed);
  cv::putText(image, label, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return image;
}

}  // namespace slamer

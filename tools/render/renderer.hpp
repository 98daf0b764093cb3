// Draws one moment of a run on the semantic map: the map (occupancy in grey,
// classes in their colours), the scan from the estimated pose, particles,
// the true and estimated poses, and recognized objects coloured as in the
// paper's Fig. 1 (no-entry line red, glass door purple, open door green).
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/map/semantic_map.hpp"
#include "common/semantic/objects.hpp"
#include "common/sensors/laser_scan.hpp"

namespace slamer {

struct RenderOptions {
  double pixels_per_cell = 1.0;  // scale of the map image
  Pose2 lidar_mount;
  // Colours (R, G, B) of recognition classes; others are drawn dark grey.
  std::map<std::string, cv::Scalar> class_colors{
      {"no_entry_line", {255, 0, 0}},       {"open_glass_door", {150, 0, 200}},
      {"closed_glass_door", {0, 200, 255}}, {"open_door", {0, 200, 0}},
      {"closed_door", {255, 0, 255}},       {"fence", {255, 140, 0}},
      {"free_space", {120, 170, 255}},      {"others", {90, 90, 90}}};
};

struct Frame {
  int64_t utime = 0;
  double elapsed = 0.0;  // [s] since the start of the log, for the caption
  std::optional<Pose2> truth;
  std::optional<Pose2> estimate;
  std::optional<LaserScan> scan;
  std::vector<Pose2> particles;
  std::optional<LineObjectSet> semantic;    // map frame
  std::optional<LineObjectSet> recognized;  // sensor frame, drawn from the estimate (or truth)
};

class FrameRenderer {
 public:
  FrameRenderer(const SemanticMap& map, RenderOptions options);
  cv::Mat draw(const Frame& frame) const;  // BGR image

 private:
  cv::Point to_pixel(const Eigen::Vector2d& world) const;
  cv::Scalar color_of(const std::string& class_name) const;  // BGR

  const SemanticMap& map_;
  RenderOptions options_;
  cv::Mat background_;
};

}  // namespace slamer

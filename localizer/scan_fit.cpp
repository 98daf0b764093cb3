#include "localizer/scan_fit.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

Pose2 sensor_in_cells(const GridGeometry& geometry, const Pose2& base, const Pose2& mount) {
  const Pose2 grid = compose(inverse(geometry.origin), compose(base, mount));
  return {grid.x / geometry.resolution, grid.y / geometry.resolution, grid.theta};
}

namespace {

// Sensor-frame points (cells) placed on the grid from a sensor pose (cells, rad).
class GridPlacer {
 public:
  GridPlacer(const GridGeometry& g, const Pose2& sensor)
      : c_(static_cast<float>(std::cos(sensor.theta))),
        s_(static_cast<float>(std::sin(sensor.theta))),
        tx_(static_cast<float>(sensor.x)),
        ty_(static_cast<float>(sensor.y)),
        width_(static_cast<float>(g.width)),
        height_(static_cast<float>(g.height)) {}
  // The cell of the point (x, y), or false when it is off the grid.
  bool cell(float x, float y, int* cx, int* cy) const {
    const float gx = c_ * x - s_ * y + tx_;
    const float gy = s_ * x + c_ * y + ty_;
    if (!(gx >= 0.0f && gy >= 0.0f && gx < width_ && gy < height_)) {
      return false;
    }
    *cx = static_cast<int>(gx);
    *cy = static_cast<int>(gy);
    return true;
  }

 private:
  float c_, s_, tx_, ty_, width_, height_;
};

}  // namespace

double scan_fit(const DistanceField& obstacles, const ScanPoints& points, const Pose2& sensor, double fit_distance,
                std::size_t step) {
  const GridPlacer place(obstacles.geometry(), sensor);
  // Levels at or below this are within fit_distance.
  const double level = std::floor(fit_distance / obstacles.step() + 1e-9);
  const int max_level = level >= DistanceField::kSaturated ? DistanceField::kSaturated - 1 : static_cast<int>(level);
  std::size_t used = 0;
  std::size_t fitting = 0;
  for (std::size_t i = 0; i < points.x.size(); i += step) {
    ++used;
    int cx = 0;
    int cy = 0;
    if (place.cell(points.x[i], points.y[i], &cx, &cy) && obstacles.level(cx, cy) <= max_level) {
      ++fitting;
    }
  }
  return used > 0 ? static_cast<double>(fitting) / static_cast<double>(used) : 0.0;
}

ScanPoints thinned_points(const ScanPoints& points, std::size_t step) {
  step = std::max<std::size_t>(step, 1);
  ScanPoints thinned;
  thinned.x.reserve(points.x.size() / step + 1);
  thinned.y.reserve(points.x.size() / step + 1);
  for (std::size_t i = 0; i < points.x.size(); i += step) {
    thinned.x.push_back(points.x[i]);
    thinned.y.push_back(points.y[i]);
  }
  return thinned;
}

double field_log_likelihood(const LikelihoodField& field, const ScanPoints& points, const Pose2& sensor) {
  // Placed as GridPlacer places them, summed as sum_terms sums (point k into
  // running sum k mod 4).
  return field.sum_placed(points.x.data(), points.y.data(), points.x.size(), static_cast<float>(std::cos(sensor.theta)),
                          static_cast<float>(std::sin(sensor.theta)), static_cast<float>(sensor.x),
                          static_cast<float>(sensor.y));
}

}  // namespace slamer

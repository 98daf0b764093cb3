#include "localizer/scan_fit.hpp"

#include <cmath>

namespace slamer {

Pose2 sensor_in_cells(const GridGeometry& geometry, const Pose2& base, const Pose2& mount) {
  const Pose2 grid = compose(inverse(geometry.origin), compose(base, mount));
  return {grid.x / geometry.resolution, grid.y / geometry.resolution, grid.theta};
}

double scan_fit(const DistanceField& obstacles, const ScanPoints& points, const Pose2& sensor, double fit_distance,
                std::size_t step) {
  const GridGeometry& g = obstacles.geometry();
  const float c = static_cast<float>(std::cos(sensor.theta));
  const float s = static_cast<float>(std::sin(sensor.theta));
  const float tx = static_cast<float>(sensor.x);
  const float ty = static_cast<float>(sensor.y);
  const float width = static_cast<float>(g.width);
  const float height = static_cast<float>(g.height);
  // Levels at or below this are within fit_distance.
  const double level = std::floor(fit_distance / obstacles.step() + 1e-9);
  const int max_level = level >= DistanceField::kSaturated ? DistanceField::kSaturated - 1 : static_cast<int>(level);
  std::size_t used = 0;
  std::size_t fitting = 0;
  for (std::size_t i = 0; i < points.x.size(); i += step) {
    ++used;
    const float gx = c * points.x[i] - s * points.y[i] + tx;
    const float gy = s * points.x[i] + c * points.y[i] + ty;
    if (gx >= 0.0f && gy >= 0.0f && gx < width && gy < height &&
        obstacles.level(static_cast<int>(gx), static_cast<int>(gy)) <= max_level) {
      ++fitting;
    }
  }
  return used > 0 ? static_cast<double>(fitting) / static_cast<double>(used) : 0.0;
}

double field_log_likelihood(const LikelihoodField& field, const ScanPoints& points, const Pose2& sensor,
                            std::size_t step) {
  const GridGeometry& g = field.geometry();
  const float c = static_cast<float>(std::cos(sensor.theta));
  const float s = static_cast<float>(std::sin(sensor.theta));
  const float tx = static_cast<float>(sensor.x);
  const float ty = static_cast<float>(sensor.y);
  const float width = static_cast<float>(g.width);
  const float height = static_cast<float>(g.height);
  double sum = 0.0;
  for (std::size_t i = 0; i < points.x.size(); i += step) {
    const float gx = c * points.x[i] - s * points.y[i] + tx;
    const float gy = s * points.x[i] + c * points.y[i] + ty;
    sum += gx >= 0.0f && gy >= 0.0f && gx < width && gy < height
               ? field.log_likelihood(static_cast<int>(gx), static_cast<int>(gy))
               : field.off_map_log_likelihood();
  }
  return sum;
}

}  // namespace slamer

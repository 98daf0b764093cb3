// ParticleFilter's beam term: a scan's end points prepared once per update
// (in grid cells, sensor frame; SLFM: also split by the class of the object
// each lies on), and each particle's LFM / SLFM log-likelihood over them
// (paper Eqs. (10)-(13)), with the sensor placed on the grid once a particle.
// Split from particle_filter.cpp for size.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "localizer/particle_filter_internal.hpp"

namespace slamer {

ParticleFilter::PreparedScan ParticleFilter::prepare(const LaserScan& scan, const LineObjectSet* objects) const {
  PreparedScan prepared;
  const double to_cells = 1.0 / geometry_.resolution;
  const float range_min = std::isfinite(scan.range_min) ? scan.range_min : 0.0f;
  for (std::size_t i = 0; i < scan.ranges.size(); i += static_cast<std::size_t>(options_.lfm.beam_step)) {
    const float r = scan.ranges[i];
    // Valid returns only: max-range beams score the same for every particle,
    // and NaN / too-close beams say nothing about the pose.
    if (!(r >= range_min && r < scan.range_max) || !std::isfinite(scan.angle(i))) {
      continue;
    }
    const double a = scan.angle(i);
    prepared.points.x.push_back(static_cast<float>(r * std::cos(a) * to_cells));
    prepared.points.y.push_back(static_cast<float>(r * std::sin(a) * to_cells));
    int field = -1;
    if (options_.mode == LocalizerMode::kSlfm && objects != nullptr) {
      // The class of the physical object the beam's point lies on, if any.
      const Eigen::Vector2d p(r * std::cos(a), r * std::sin(a));
      double best = options_.slfm.support;
      for (const LineObject& o : objects->objects) {
        if (o.kind != LineKind::kPhysical) {
          continue;
        }
        const double d = distance_to_segment(p, o.start, o.end);
        const int label = most_likely(o.probs);
        if (d <= best && label >= 0 && static_cast<std::size_t>(label) < objects->class_names.size()) {
          best = d;
          field = -1;
          const auto mapped = options_.slamer.class_map.find(objects->class_names[static_cast<std::size_t>(label)]);
          if (mapped != options_.slamer.class_map.end()) {
            const auto it = std::find(map_classes_.begin(), map_classes_.end(), mapped->second);
            field = it == map_classes_.end() ? -1 : static_cast<int>(it - map_classes_.begin());
          }
        }
      }
    }
    if (field >= 0) {
      prepared.by_field.resize(std::max(prepared.by_field.size(), static_cast<std::size_t>(field) + 1));
      prepared.by_field[static_cast<std::size_t>(field)].x.push_back(prepared.points.x.back());
      prepared.by_field[static_cast<std::size_t>(field)].y.push_back(prepared.points.y.back());
    }
  }
  return prepared;
}

Pose2 ParticleFilter::sensor_on_grid(const Pose2& pose, double* c, double* s) const {
  // compose(grid_from_world_, compose(pose, mount_)) written out with one sine
  // and cosine, not four: the origin's are kept, and with the mount and the
  // origin unrotated (as nearly always) the grid's heading is the particle's
  // to the bit. The same arithmetic as compose, so the same numbers.
  const double pose_c = std::cos(pose.theta), pose_s = std::sin(pose.theta);
  const Pose2 sensor{pose.x + pose_c * mount_.x - pose_s * mount_.y, pose.y + pose_s * mount_.x + pose_c * mount_.y,
                     wrap_angle(pose.theta + mount_.theta)};
  const double gc = grid_from_world_cos_, gs = grid_from_world_sin_;
  const Pose2 grid{grid_from_world_.x + gc * sensor.x - gs * sensor.y,
                   grid_from_world_.y + gs * sensor.x + gc * sensor.y,
                   wrap_angle(grid_from_world_.theta + sensor.theta)};
  const bool same_heading = std::bit_cast<uint64_t>(grid.theta) == std::bit_cast<uint64_t>(pose.theta);
  *c = same_heading ? pose_c : std::cos(grid.theta);
  *s = same_heading ? pose_s : std::sin(grid.theta);
  return grid;
}

double ParticleFilter::beams_log_likelihood(const Pose2& pose, const PreparedScan& scan) const {
  // Sensor pose in grid cells: one transform per particle, then a multiply-add per beam.
  double grid_c = 1.0, grid_s = 0.0;
  const Pose2 grid = sensor_on_grid(pose, &grid_c, &grid_s);
  const float c = static_cast<float>(grid_c);
  const float s = static_cast<float>(grid_s);
  const float tx = static_cast<float>(grid.x / geometry_.resolution);
  const float ty = static_cast<float>(grid.y / geometry_.resolution);
  const std::vector<float>& px = scan.points.x;
  const std::vector<float>& py = scan.points.y;
  if (options_.mode != LocalizerMode::kSlfm) {
    return options_.lfm.beam_weight * field_.sum_placed(px.data(), py.data(), px.size(), c, s, tx, ty);
  }
  // Beams of an unknown class are left out: the exponential model, the same for every pose.
  double sum = 0.0;
  for (std::size_t f = 0; f < scan.by_field.size(); ++f) {
    const ScanPoints& points = scan.by_field[f];
    sum += class_fields_[f].sum_placed(points.x.data(), points.y.data(), points.x.size(), c, s, tx, ty);
  }
  return options_.lfm.beam_weight * sum;
}
double ParticleFilter::scan_log_likelihood(const Pose2& pose, const LaserScan& scan) const {
  return beams_log_likelihood(pose, prepare(scan, nullptr));
}

}  // namespace slamer

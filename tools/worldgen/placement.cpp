#include "tools/worldgen/placement.hpp"

#include <algorithm>
#include <cmath>

#include "common/geometry/se2.hpp"

namespace slamer {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

double segment_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1) {
  const double d1 = cross(a1 - a0, b0 - a0);
  const double d2 = cross(a1 - a0, b1 - a0);
  const double d3 = cross(b1 - b0, a0 - b0);
  const double d4 = cross(b1 - b0, a1 - b0);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) {
    return 0.0;
  }
  return std::min({distance_to_segment(a0, b0, b1), distance_to_segment(a1, b0, b1), distance_to_segment(b0, a0, a1),
                   distance_to_segment(b1, a0, a1)});
}

bool Placement::fits(const KeepOut& s) const {
  const Eigen::Vector2d along = (s.b - s.a).normalized();
  const Eigen::Vector2d side(-along.y(), along.x());
  constexpr double kMargin = 0.05;
  for (const double u : {-1.0, 1.0}) {
    for (const Eigen::Vector2d& end : {Eigen::Vector2d(s.a - along * s.half), Eigen::Vector2d(s.b + along * s.half)}) {
      const Eigen::Vector2d corner = end + u * s.half * side;
      if (corner.x() < x0_ + kMargin || corner.x() > x1_ - kMargin || corner.y() < y0_ + kMargin ||
          corner.y() > y1_ - kMargin) {
        return false;
      }
    }
  }
  constexpr double kGap = 0.15;
  return std::all_of(taken_.begin(), taken_.end(),
                     [&](const KeepOut& t) { return segment_distance(s.a, s.b, t.a, t.b) > s.half + t.half + kGap; });
}

std::optional<KeepOut> Placement::random_segment(std::mt19937& rng, double length_min, double length_max,
                                                 double thickness, double aligned) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double room = std::max(x1_ - x0_, y1_ - y0_);
  for (int attempt = 0; attempt < 40; ++attempt) {
    const double length = std::min(length_min + unit(rng) * (length_max - length_min), room - thickness - 0.2);
    if (length <= 0.1) {
      return std::nullopt;
    }
    const double angle = unit(rng) < aligned ? (unit(rng) < 0.5 ? 0.0 : M_PI / 2) : unit(rng) * M_PI;
    // One draw a statement, y first (see GlobalProposals::uniform): the order the worlds
    // so far were generated with, now the same with every compiler.
    const double along_y = unit(rng);
    const double along_x = unit(rng);
    const Eigen::Vector2d center(x0_ + along_x * (x1_ - x0_), y0_ + along_y * (y1_ - y0_));
    const Eigen::Vector2d half_along = 0.5 * length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const KeepOut s{center - half_along, center + half_along, thickness / 2.0};
    if (fits(s)) {
      taken_.push_back(s);
      return s;
    }
  }
  return std::nullopt;
}

}  // namespace slamer

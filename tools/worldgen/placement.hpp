// Places thick segments (furniture, fences, no-entry lines) at random inside a
// room's rectangle, clear of what is reserved there (the route, door leaves)
// and of each other. Part of the world generator (building.hpp).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <random>
#include <vector>

namespace slamer {

struct KeepOut {  // a thick segment: everything within `half` of a-b
  Eigen::Vector2d a{0.0, 0.0}, b{0.0, 0.0};
  double half = 0.0;
};

// Shortest distance between segments a0-a1 and b0-b1 (0 if they cross).
double segment_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                        const Eigen::Vector2d& b1);

class Placement {
 public:
  Placement(double x0, double y0, double x1, double y1) : x0_(x0), y0_(y0), x1_(x1), y1_(y1) {}
  void reserve(const KeepOut& area) { taken_.push_back(area); }
  // A segment of length in [length_min, length_max] (shortened to fit) and the given thickness,
  // along the room's axes with probability `aligned`, else at any angle; nullopt after 40 tries.
  std::optional<KeepOut> random_segment(std::mt19937& rng, double length_min, double length_max, double thickness,
                                        double aligned);

 private:
  bool fits(const KeepOut& s) const;

  double x0_, y0_, x1_, y1_;
  std::vector<KeepOut> taken_;
};

}  // namespace slamer

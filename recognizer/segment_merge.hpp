// Groups near-duplicate segments so that the result does not depend on the
// order they come in: union-find over the symmetric "near-duplicate"
// relation, so each group is the same set whatever the order.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace slamer {

struct Segment2 {
  Eigen::Vector2d a{0.0, 0.0};
  Eigen::Vector2d b{0.0, 0.0};
};

// Distance from a point to a segment (perpendicular where it projects inside).
double distance_to_segment(const Eigen::Vector2d& p, const Segment2& s);
// Angle between two segments' directions, folded to [0, pi/2].
double orientation_difference(const Segment2& s, const Segment2& t);

// Groups of indices of segments linked by `near` (directly or through others),
// each group sorted, groups sorted by their first index.
std::vector<std::vector<int>> group_segments(const std::vector<Segment2>& segments,
                                             const std::function<bool(const Segment2&, const Segment2&)>& near);

}  // namespace slamer

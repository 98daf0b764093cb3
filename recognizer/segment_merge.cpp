#include "recognizer/segment_merge.hpp"

#include "common/geometry/se2.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>

namespace slamer {

double distance_to_segment(const Eigen::Vector2d& p, const Segment2& s) {
  return slamer::distance_to_segment(p, s.a, s.b);
}

double orientation_difference(const Segment2& s, const Segment2& t) {
  const Eigen::Vector2d u = s.b - s.a;
  const Eigen::Vector2d v = t.b - t.a;
  double d = std::abs(std::atan2(u.y(), u.x()) - std::atan2(v.y(), v.x()));
  d = std::fmod(d, std::numbers::pi);
  return std::min(d, std::numbers::pi - d);
}

std::vector<std::vector<int>> group_segments(const std::vector<Segment2>& segments,
                                             const std::function<bool(const Segment2&, const Segment2&)>& near) {
  const int n = static_cast<int>(segments.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (near(segments[static_cast<std::size_t>(i)], segments[static_cast<std::size_t>(j)])) {
        const int ri = root(i);
        const int rj = root(j);
        parent[static_cast<std::size_t>(std::max(ri, rj))] = std::min(ri, rj);
      }
    }
  }
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < n; ++i) {
    groups[root(i)].push_back(i);
  }
  std::vector<std::vector<int>> result;
  for (auto& [first, members] : groups) {
    result.push_back(std::move(members));
  }
  return result;
}

}  // namespace slamer

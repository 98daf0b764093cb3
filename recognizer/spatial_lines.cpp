#include "recognizer/spatial_lines.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slamer {
namespace {

// Next (step +1) or previous (step -1) beam that tells something, or -1.
int neighbour(const PreparedScan& scan, int beam, int step) {
  for (int k = beam + step; k >= 0 && k < static_cast<int>(scan.state.size()); k += step) {
    if (scan.state[static_cast<std::size_t>(k)] != BeamState::kUnknown) {
      return k;
    }
  }
  return -1;
}

bool can_pass_next_to(const PreparedScan& scan, int beam, int step, double margin) {
  const int k = neighbour(scan, beam, step);
  if (k < 0) {
    return false;
  }
  const BeamState state = scan.state[static_cast<std::size_t>(k)];
  return state == BeamState::kNoReturn ||
         (state == BeamState::kHit &&
          (scan.point[static_cast<std::size_t>(k)] - scan.point[static_cast<std::size_t>(beam)]).norm() >= margin);
}

}  // namespace

std::vector<SpatialLine> spatial_candidates(const PreparedScan& scan, double angle_increment,
                                            const OrientationHistogram& histogram, const RecognizerOptions& options) {
  std::vector<int> left_ends;
  std::vector<int> right_ends;
  for (const int beam : scan.hits) {
    if (can_pass_next_to(scan, beam, +1, options.pass_margin)) {
      left_ends.push_back(beam);
    }
    if (can_pass_next_to(scan, beam, -1, options.pass_margin)) {
      right_ends.push_back(beam);
    }
  }
  // Beams told-something prefix counts, to know how many failures are allowed.
  std::vector<int> known(scan.state.size() + 1, 0);
  for (std::size_t k = 0; k < scan.state.size(); ++k) {
    known[k + 1] = known[k] + (scan.state[k] != BeamState::kUnknown ? 1 : 0);
  }
  // Beyond this many beams the two ends are half a turn apart: the line would pass behind the sensor.
  const double half_turn = std::abs(angle_increment) > 0.0 ? std::floor(std::numbers::pi / std::abs(angle_increment))
                                                           : 0.0;  // NaN compares false: no pairs
  const int max_span =
      half_turn >= 1.0 ? static_cast<int>(std::min(half_turn - 1.0, static_cast<double>(scan.state.size()))) : 0;
  const double min2 = options.spatial_min_length * options.spatial_min_length;
  const double max2 = options.spatial_max_length * options.spatial_max_length;
  std::vector<SpatialLine> lines;
  for (const int i : left_ends) {
    const Eigen::Vector2d& a = scan.point[static_cast<std::size_t>(i)];
    for (auto it = std::upper_bound(right_ends.begin(), right_ends.end(), i);
         it != right_ends.end() && *it - i <= max_span; ++it) {
      const int j = *it;
      const Eigen::Vector2d& b = scan.point[static_cast<std::size_t>(j)];
      const Eigen::Vector2d ab = b - a;
      const double length2 = ab.squaredNorm();
      if (length2 < min2 || length2 > max2 ||
          !histogram.agrees(std::atan2(ab.y(), ab.x()), options.histogram_min_fraction)) {
        continue;
      }
      // Unit normal pointing away from the sensor (at the origin).
      Eigen::Vector2d normal(-ab.y(), ab.x());
      normal /= std::sqrt(length2);
      if (normal.dot(a) < 0.0) {
        normal = -normal;
      }
      const int between = known[static_cast<std::size_t>(j)] - known[static_cast<std::size_t>(i) + 1];
      const int allowed_failures = static_cast<int>(std::floor((1.0 - options.min_pass_fraction) * between));
      int passing = 0;
      int failing = 0;
      for (int k = i + 1; k < j && failing <= allowed_failures; ++k) {
        switch (scan.state[static_cast<std::size_t>(k)]) {
          case BeamState::kUnknown:
            break;
          case BeamState::kNoReturn:
            ++passing;
            break;
          case BeamState::kBlocked:
            ++failing;
            break;
          case BeamState::kHit:
            if (normal.dot(scan.point[static_cast<std::size_t>(k)] - a) >= options.pass_margin) {
              ++passing;
            } else {
              ++failing;
            }
            break;
        }
      }
      if (failing <= allowed_failures && passing >= options.min_pass_beams &&
          passing >= options.min_pass_fraction * between) {
        lines.push_back({{a, b}, i, j, passing, between});
      }
    }
  }
  return lines;
}

std::vector<SpatialLine> merge_spatial_lines(const std::vector<SpatialLine>& candidates,
                                             const RecognizerOptions& options) {
  std::vector<Segment2> segments;
  for (const SpatialLine& line : candidates) {
    segments.push_back(line.segment);
  }
  const double d = options.merge_distance;
  const auto near = [d](const Segment2& s, const Segment2& t) {
    return ((s.a - t.a).norm() <= d && (s.b - t.b).norm() <= d) || ((s.a - t.b).norm() <= d && (s.b - t.a).norm() <= d);
  };
  std::vector<SpatialLine> merged;
  for (const std::vector<int>& group : group_segments(segments, near)) {
    const SpatialLine* best = nullptr;
    for (const int member : group) {
      const SpatialLine& line = candidates[static_cast<std::size_t>(member)];
      if (best == nullptr || line.passing_beams > best->passing_beams ||
          (line.passing_beams == best->passing_beams &&
           std::tie(line.first_beam, line.last_beam) < std::tie(best->first_beam, best->last_beam))) {
        best = &line;
      }
    }
    merged.push_back(*best);
  }
  std::sort(merged.begin(), merged.end(), [](const SpatialLine& x, const SpatialLine& y) {
    return std::tie(x.first_beam, x.last_beam) < std::tie(y.first_beam, y.last_beam);
  });
  return merged;
}

}  // namespace slamer

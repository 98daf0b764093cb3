#include "recognizer/physical_lines.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace slamer {
namespace {

// Beams whose points lie within `distance` of the segment.
std::vector<int> support_of(const PreparedScan& scan, const Segment2& segment, double distance) {
  std::vector<int> support;
  for (const int beam : scan.hits) {
    if (distance_to_segment(scan.point[static_cast<std::size_t>(beam)], segment) <= distance) {
      support.push_back(beam);
    }
  }
  return support;
}

// Points within `distance` of the infinite line through `segment` that form a
// contiguous run along it (gaps up to `max_gap`) overlapping the segment: the
// line's full extent even where Hough found only a piece of it.
std::vector<int> grow_along_line(const PreparedScan& scan, const Segment2& segment, double distance, double max_gap) {
  const Eigen::Vector2d direction = (segment.b - segment.a).normalized();
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  const double length = (segment.b - segment.a).norm();
  std::vector<std::pair<double, int>> along;
  for (const int beam : scan.hits) {
    const Eigen::Vector2d d = scan.point[static_cast<std::size_t>(beam)] - segment.a;
    if (std::abs(d.dot(normal)) <= distance) {
      along.emplace_back(d.dot(direction), beam);
    }
  }
  std::sort(along.begin(), along.end());
  // The run of points, split at gaps, that overlaps [0, length].
  std::vector<int> run;
  std::vector<int> best;
  double run_start = 0.0;
  for (std::size_t i = 0; i < along.size(); ++i) {
    if (i > 0 && along[i].first - along[i - 1].first > max_gap) {
      if (run_start <= length && along[i - 1].first >= 0.0 && run.size() > best.size()) {
        best = run;
      }
      run.clear();
    }
    if (run.empty()) {
      run_start = along[i].first;
    }
    run.push_back(along[i].second);
  }
  if (!along.empty() && run_start <= length && along.back().first >= 0.0 && run.size() > best.size()) {
    best = run;
  }
  std::sort(best.begin(), best.end());
  return best;
}

// Least-squares line through the points (principal axis), clipped to their extent.
Segment2 fit(const PreparedScan& scan, const std::vector<int>& beams) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const int beam : beams) {
    mean += scan.point[static_cast<std::size_t>(beam)];
  }
  mean /= static_cast<double>(beams.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const int beam : beams) {
    const Eigen::Vector2d d = scan.point[static_cast<std::size_t>(beam)] - mean;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  const Eigen::Vector2d direction = solver.eigenvectors().col(1);  // largest eigenvalue
  double lo = 0.0;
  double hi = 0.0;
  for (const int beam : beams) {
    const double s = (scan.point[static_cast<std::size_t>(beam)] - mean).dot(direction);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {mean + lo * direction, mean + hi * direction};
}

double coverage_of(const PreparedScan& scan, const Segment2& segment, const std::vector<int>& beams, double step) {
  const Eigen::Vector2d direction = segment.b - segment.a;
  const double length = direction.norm();
  if (length <= 0.0) {
    return 0.0;
  }
  std::vector<double> along;
  for (const int beam : beams) {
    along.push_back((scan.point[static_cast<std::size_t>(beam)] - segment.a).dot(direction) / length);
  }
  std::sort(along.begin(), along.end());
  double covered = 0.0;
  double reach = 0.0;  // covered up to here
  for (const double s : along) {
    const double from = std::max({s - step / 2.0, reach, 0.0});
    const double to = std::min(s + step / 2.0, length);
    if (to > from) {
      covered += to - from;
    }
    reach = std::max(reach, to);
  }
  return std::min(1.0, covered / length);
}

// Puts a segment's end points in a canonical order (smaller bearing first).
Segment2 canonical(const Segment2& s) {
  return std::atan2(s.a.y(), s.a.x()) <= std::atan2(s.b.y(), s.b.x()) ? s : Segment2{s.b, s.a};
}

}  // namespace

std::vector<Segment2> hough_segments(const PreparedScan& scan, const RecognizerOptions& options) {
  const double res = options.image_resolution;
  const int size = static_cast<int>(std::ceil(2.0 * options.image_extent / res));
  cv::Mat image = cv::Mat::zeros(size, size, CV_8UC1);
  for (const int beam : scan.hits) {
    const Eigen::Vector2d& p = scan.point[static_cast<std::size_t>(beam)];
    const double col = std::floor((p.x() + options.image_extent) / res);
    const double row = std::floor((options.image_extent - p.y()) / res);
    if (col >= 0.0 && row >= 0.0 && col < size && row < size) {  // never index with NaN or out of range
      image.at<uint8_t>(static_cast<int>(row), static_cast<int>(col)) = 255;
    }
  }
  std::vector<cv::Vec4i> lines;
  cv::HoughLinesP(image, lines, std::max(1.0, options.hough_rho / res), options.hough_theta, options.hough_threshold,
                  options.hough_min_length / res, options.hough_max_gap / res);
  std::vector<Segment2> segments;
  for (const cv::Vec4i& l : lines) {
    const auto to_metres = [&](int col, int row) {
      return Eigen::Vector2d((col + 0.5) * res - options.image_extent, options.image_extent - (row + 0.5) * res);
    };
    segments.push_back({to_metres(l[0], l[1]), to_metres(l[2], l[3])});
  }
  return segments;
}

std::vector<PhysicalLine> refine_physical_lines(const PreparedScan& scan, const std::vector<Segment2>& candidates,
                                                const RecognizerOptions& options) {
  // Refit every candidate to its support, grow it along its line over
  // contiguous points, and refit again.
  std::vector<Segment2> fitted;
  std::vector<std::vector<int>> supports;
  for (const Segment2& candidate : candidates) {
    std::vector<int> support = support_of(scan, candidate, options.support_distance);
    if (static_cast<int>(support.size()) < options.physical_min_points) {
      continue;
    }
    Segment2 segment = fit(scan, support);
    support = grow_along_line(scan, segment, options.support_distance, options.hough_max_gap);
    if (static_cast<int>(support.size()) < options.physical_min_points) {
      continue;
    }
    segment = fit(scan, support);
    support = grow_along_line(scan, segment, options.support_distance, options.hough_max_gap);
    if (static_cast<int>(support.size()) < options.physical_min_points) {
      continue;
    }
    fitted.push_back(canonical(fit(scan, support)));
    supports.push_back(std::move(support));
  }
  const auto near = [&](const Segment2& s, const Segment2& t) {
    if (orientation_difference(s, t) > options.merge_angle) {
      return false;
    }
    const double d = options.merge_distance;
    // Overlapping or touching, and one lies along the other.
    return (distance_to_segment(s.a, t) <= d || distance_to_segment(s.b, t) <= d || distance_to_segment(t.a, s) <= d ||
            distance_to_segment(t.b, s) <= d);
  };
  std::vector<PhysicalLine> lines;
  for (const std::vector<int>& group : group_segments(fitted, near)) {
    std::vector<int> beams;
    for (const int member : group) {
      beams.insert(beams.end(), supports[static_cast<std::size_t>(member)].begin(),
                   supports[static_cast<std::size_t>(member)].end());
    }
    std::sort(beams.begin(), beams.end());
    beams.erase(std::unique(beams.begin(), beams.end()), beams.end());
    const Segment2 segment = canonical(fit(scan, beams));
    if ((segment.b - segment.a).norm() < options.physical_min_length) {
      continue;
    }
    lines.push_back(
        {segment, static_cast<int>(beams.size()), coverage_of(scan, segment, beams, options.coverage_step)});
  }
  std::sort(lines.begin(), lines.end(), [](const PhysicalLine& x, const PhysicalLine& y) {
    return std::tie(x.segment.a.x(), x.segment.a.y(), x.segment.b.x(), x.segment.b.y()) <
           std::tie(y.segment.a.x(), y.segment.a.y(), y.segment.b.x(), y.segment.b.y());
  });
  return lines;
}

}  // namespace slamer

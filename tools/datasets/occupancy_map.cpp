#include "tools/datasets/occupancy_map.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"

namespace slamer {
namespace {

bool usable(const LaserScan& scan, float r) {
  return std::isfinite(r) && r >= scan.range_min && r <= scan.range_max;
}

// Bounding box of the poses and beam end points, plus the margin.
GridGeometry grid_for(const std::vector<LaserScan>& scans, const std::vector<Pose2>& poses,
                      const MapgenOptions& options) {
  double lo_x = std::numeric_limits<double>::infinity();
  double lo_y = lo_x;
  double hi_x = -lo_x;
  double hi_y = -lo_x;
  const auto add = [&](const Eigen::Vector2d& p) {
    lo_x = std::min(lo_x, p.x());
    lo_y = std::min(lo_y, p.y());
    hi_x = std::max(hi_x, p.x());
    hi_y = std::max(hi_y, p.y());
  };
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const Pose2 laser = compose(poses[k], options.laser_mount);
    add({laser.x, laser.y});
    for (std::size_t i = 0; i < scans[k].ranges.size(); ++i) {
      const float r = scans[k].ranges[i];
      if (usable(scans[k], r)) {
        const double a = scans[k].angle(i);
        add(transform_point(laser, {r * std::cos(a), r * std::sin(a)}));
      }
    }
  }
  GridGeometry g;
  g.resolution = options.resolution;
  if (!std::isfinite(lo_x)) {
    lo_x = lo_y = hi_x = hi_y = 0.0;
  }
  const double m = options.margin;
  g.origin = {std::floor((lo_x - m) / g.resolution) * g.resolution,
              std::floor((lo_y - m) / g.resolution) * g.resolution, 0.0};
  g.width = static_cast<int>(std::ceil((hi_x + m - g.origin.x) / g.resolution));
  g.height = static_cast<int>(std::ceil((hi_y + m - g.origin.y) / g.resolution));
  if (static_cast<double>(g.width) * g.height > 4e8) {
    throw std::invalid_argument("the map would have more than 4e8 cells: check the poses and --resolution");
  }
  return g;
}

}  // namespace

OccupancyCounts build_occupancy(const std::vector<LaserScan>& scans, const std::vector<Pose2>& poses,
                                const MapgenOptions& options) {
  if (scans.size() != poses.size()) {
    throw std::invalid_argument("build_occupancy: as many poses as scans are needed");
  }
  if (!(options.resolution > 0.0)) {
    throw std::invalid_argument("the map resolution must be > 0");
  }
  OccupancyCounts counts;
  counts.geometry = grid_for(scans, poses, options);
  const GridGeometry& g = counts.geometry;
  counts.hits.assign(g.size(), 0);
  counts.passes.assign(g.size(), 0);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const Pose2 laser = compose(poses[k], options.laser_mount);
    const Eigen::Vector2d start = g.to_grid({laser.x, laser.y});
    const int x0 = static_cast<int>(std::floor(start.x()));
    const int y0 = static_cast<int>(std::floor(start.y()));
    for (std::size_t i = 0; i < scans[k].ranges.size(); ++i) {
      const float r = scans[k].ranges[i];
      if (!usable(scans[k], r)) {
        continue;
      }
      const double a = scans[k].angle(i);
      const Eigen::Vector2d end = g.to_grid(transform_point(laser, {r * std::cos(a), r * std::sin(a)}));
      const int x1 = static_cast<int>(std::floor(end.x()));
      const int y1 = static_cast<int>(std::floor(end.y()));
      // Bresenham from the laser's cell to the end cell (exclusive).
      int x = x0;
      int y = y0;
      const int dx = std::abs(x1 - x0);
      const int dy = -std::abs(y1 - y0);
      const int sx = x0 < x1 ? 1 : -1;
      const int sy = y0 < y1 ? 1 : -1;
      int err = dx + dy;
      while (x != x1 || y != y1) {
        if (g.contains(x, y)) {
          ++counts.passes[g.index(x, y)];
        }
        const int e2 = 2 * err;
        if (e2 >= dy) {
          err += dy;
          x += sx;
        }
        if (e2 <= dx) {
          err += dx;
          y += sy;
        }
      }
      if (g.contains(x1, y1)) {
        ++counts.hits[g.index(x1, y1)];
      }
    }
  }
  return counts;
}

std::vector<Occupancy> classify_cells(const OccupancyCounts& counts, const MapgenOptions& options) {
  std::vector<Occupancy> cells(counts.geometry.size(), Occupancy::kUnknown);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const double seen = static_cast<double>(counts.hits[i]) + counts.passes[i];
    if (counts.hits[i] > 0 && counts.hits[i] >= options.occupied_fraction * seen) {
      cells[i] = Occupancy::kOccupied;
    } else if (seen > 0) {
      cells[i] = Occupancy::kFree;
    }
  }
  return cells;
}

void write_grid_map(const GridGeometry& g, const std::vector<Occupancy>& cells, const std::string& comment,
                    const std::string& directory) {
  cv::Mat occupancy(g.height, g.width, CV_8UC1, cv::Scalar(205));
  cv::Mat semantic(g.height, g.width, CV_8UC3, cv::Scalar(205, 205, 205));
  for (int y = 0; y < g.height; ++y) {
    const int row = g.height - 1 - y;  // image row 0 is the top
    for (int x = 0; x < g.width; ++x) {
      const Occupancy cell = cells[g.index(x, y)];
      if (cell == Occupancy::kOccupied) {
        occupancy.at<uint8_t>(row, x) = 0;
        semantic.at<cv::Vec3b>(row, x) = {0, 0, 0};
      } else if (cell == Occupancy::kFree) {
        occupancy.at<uint8_t>(row, x) = 254;
        semantic.at<cv::Vec3b>(row, x) = {254, 254, 254};
      }
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  const std::vector<int> png_options{cv::IMWRITE_PNG_COMPRESSION, 9};
  if (!cv::imwrite(directory + "/map.pgm", occupancy) ||
      !cv::imwrite(directory + "/semantic.png", semantic, png_options)) {
    throw std::runtime_error("cannot write the map images into " + directory);
  }
  std::ofstream yaml(directory + "/map.yaml");
  yaml.precision(10);
  yaml << "# " << comment << "\n"
       << "image: map.pgm\nresolution: " << g.resolution << "\norigin: [" << g.origin.x << ", " << g.origin.y
       << ", 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
       << "semantic:\n  image: semantic.png\n  classes:\n    - {name: others, color: [0, 0, 0]}\n";
  if (!yaml) {
    throw std::runtime_error("cannot write " + directory + "/map.yaml");
  }
}

void write_occupancy_map(const OccupancyCounts& counts, const MapgenOptions& options, const std::string& directory) {
  write_grid_map(counts.geometry, classify_cells(counts, options),
                 "Generated by slamer-mapgen from a log's scans at its reference poses.", directory);
}

ScansAtPoses read_scans_at_poses(const std::string& lcm_path, const std::string& lidar_channel,
                                 const std::string& pose_channel, double max_pose_gap) {
  EventLogReader reader(lcm_path);
  std::vector<LaserScan> scans;
  std::vector<std::pair<int64_t, Pose2>> references;
  while (const std::optional<LogEvent> event = reader.next()) {
    if (event->channel == lidar_channel) {
      laser_scan_t m;
      if (decode_message(event->data.data(), event->data.size(), &m) == DecodeStatus::kOk) {
        scans.push_back(from_message(m));
      }
    } else if (event->channel == pose_channel) {
      pose_estimate_t m;
      if (decode_message(event->data.data(), event->data.size(), &m) == DecodeStatus::kOk) {
        references.push_back({m.utime, {m.x, m.y, m.theta}});
      }
    }
  }
  std::sort(references.begin(), references.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ScansAtPoses result;
  const auto gap = static_cast<int64_t>(max_pose_gap * 1e6);
  for (LaserScan& scan : scans) {
    const auto after = std::lower_bound(references.begin(), references.end(), scan.utime,
                                        [](const auto& r, int64_t t) { return r.first < t; });
    std::optional<Pose2> pose;
    if (after != references.end() && after->first == scan.utime) {
      pose = after->second;
    } else if (after != references.end() && after != references.begin() && after->first - (after - 1)->first <= gap) {
      const auto before = after - 1;
      const double t =
          static_cast<double>(scan.utime - before->first) / static_cast<double>(after->first - before->first);
      pose = interpolate(before->second, after->second, t);
    }
    if (pose) {
      result.scans.push_back(std::move(scan));
      result.poses.push_back(*pose);
    } else {
      ++result.scans_without_pose;
    }
  }
  return result;
}

}  // namespace slamer

// slamer-mapgen's core: an occupancy grid ray-cast from scans at known poses
// (a log's LIDAR at its GROUND_TRUTH), written as a map_server map the stack
// loads: map.pgm (0 occupied, 254 free, 205 unknown), semantic.png (occupied
// cells in the `others` colour, the only class) and map.yaml with the origin
// at the lower-left corner of the lower-left pixel.
//
// Each finite beam marks the cells it passes as seen free and its end cell as
// hit (Bresenham from the laser to the end point); beams with no return
// (+inf), too close or past range_max mark nothing. A cell is occupied when
// hits / (hits + passes) >= occupied_fraction, free when it was passed
// otherwise, unknown when never seen.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/map/grid_geometry.hpp"
#include "common/map/semantic_map.hpp"
#include "common/sensors/laser_scan.hpp"

namespace slamer {

struct MapgenOptions {
  double resolution = 0.05;         // [m per cell]
  double margin = 1.0;              // [m] around every pose and beam end
  double occupied_fraction = 0.25;  // of the times a cell was seen, how often it must be hit
  Pose2 laser_mount;                // the laser on the base
  double max_pose_gap = 0.5;        // [s] a scan's pose is interpolated between references this close
};

struct OccupancyCounts {
  GridGeometry geometry;
  std::vector<uint32_t> hits;    // per cell
  std::vector<uint32_t> passes;  // per cell
};

// Scans and the base poses they were taken at (same length). Throws
// std::invalid_argument for mismatched sizes or a non-positive resolution.
OccupancyCounts build_occupancy(const std::vector<LaserScan>& scans, const std::vector<Pose2>& poses,
                                const MapgenOptions& options);

// The cells of the counts by the rule above.
std::vector<Occupancy> classify_cells(const OccupancyCounts& counts, const MapgenOptions& options);

// Writes map.pgm, semantic.png and map.yaml into `directory` (created if
// missing); throws std::runtime_error if it cannot.
void write_grid_map(const GridGeometry& geometry, const std::vector<Occupancy>& cells, const std::string& comment,
                    const std::string& directory);
void write_occupancy_map(const OccupancyCounts& counts, const MapgenOptions& options, const std::string& directory);

// A log's scans with the reference pose at each scan's utime (exact, or
// interpolated between two references at most max_pose_gap apart); scans
// without one are left out and counted.
struct ScansAtPoses {
  std::vector<LaserScan> scans;
  std::vector<Pose2> poses;
  int64_t scans_without_pose = 0;
};
// Throws std::runtime_error if the log cannot be read.
ScansAtPoses read_scans_at_poses(const std::string& lcm_path, const std::string& lidar_channel,
                                 const std::string& pose_channel, double max_pose_gap);

}  // namespace slamer

// Bounded Euclidean distance field of a grid: for every cell, the distance in
// metres from its centre to the nearest centre of a target cell, exact (the
// lower envelope of parabolas of Felzenszwalb & Huttenlocher, "Distance
// Transforms of Sampled Functions", 2012, not a chamfer mask) up to
// `max_distance`, and saturated beyond it.
//
// The measurement models only need distances up to a few sigma (paper Eqs.
// (10)-(11): the likelihood field of the LFM; Eq. (7): SLAMER's per-class map
// prior), so a map stores 256 levels per cell, 0 .. max_distance in steps of
// max_distance / 255, the last level meaning "at or beyond max_distance".
// Cells are kept in 32 x 32 tiles, and a tile whose cells are all one level
// (open space, unknown space, far from any door) shares one block with every
// other such tile. A 200 m x 200 m map at 5 cm costs at most 16 MB per field
// and far less when much of it is far from targets. The transform runs in
// bands of 32 rows with a margin of max_distance, so building a field never
// holds more than a band of intermediate values.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "common/map/grid_geometry.hpp"

namespace slamer {

class DistanceField {
 public:
  static constexpr int kTileBits = 5;
  static constexpr int kTileSize = 1 << kTileBits;  // cells per tile side
  static constexpr int kSaturated = 255;            // level of "at or beyond max_distance"

  // Fills `row` (geometry.width entries) for grid row y: non-zero where the cell is a target.
  using TargetRows = std::function<void(int y, uint8_t* row)>;

  DistanceField() = default;
  DistanceField(DistanceField&&) = default;
  DistanceField& operator=(DistanceField&&) = default;
  DistanceField(const DistanceField&) = delete;  // tiles point into blocks it owns; share it instead
  DistanceField& operator=(const DistanceField&) = delete;
  // Throws std::invalid_argument unless max_distance > 0 and finite.
  DistanceField(const GridGeometry& geometry, const TargetRows& targets, double max_distance);
  // `is_target` has geometry.size() entries (index = geometry.index(x, y)).
  DistanceField(const GridGeometry& geometry, const std::vector<uint8_t>& is_target, double max_distance);

  const GridGeometry& geometry() const { return geometry_; }
  bool has_targets() const { return has_targets_; }
  double max_distance() const { return max_distance_; }
  double step() const { return step_; }  // [m per level]

  // The lookup of level() by value: a hot loop takes one copy, so the tile
  // table stays in registers (the build's -fno-strict-aliasing, which LCM's
  // decoders need, would reload it through the field after every store).
  struct Levels {
    const uint8_t* const* tiles;
    std::size_t tiles_x;
    uint8_t operator()(int x, int y) const {
      const std::size_t tile =
          static_cast<std::size_t>(y >> kTileBits) * tiles_x + static_cast<std::size_t>(x >> kTileBits);
      return tiles[tile][((y & (kTileSize - 1)) << kTileBits) | (x & (kTileSize - 1))];
    }
  };
  Levels levels() const { return {tiles_.data(), static_cast<std::size_t>(tiles_x_)}; }
  // The quantized distance of an on-map cell, 0 .. kSaturated.
  uint8_t level(int x, int y) const { return levels()(x, y); }
  // Distance [m] at an on-map cell, at most max_distance (also when there is no target).
  float at(int x, int y) const { return static_cast<float>(level(x, y) * step_); }
  // Distance [m] of the cell containing a world point; nullopt off the map.
  std::optional<float> at_world(const Eigen::Vector2d& world) const;

  // Bytes held by the field (tiles, shared blocks and the tile table).
  std::size_t memory_bytes() const;
  std::size_t distinct_tiles() const { return distinct_tiles_; }

 private:
  void add_band(int first_tile_row, const std::vector<uint8_t>& band, int rows);
  uint8_t* new_block();

  GridGeometry geometry_;
  double max_distance_ = 1.0;
  double step_ = 1.0 / kSaturated;
  bool has_targets_ = false;
  int tiles_x_ = 0;
  std::vector<const uint8_t*> tiles_;               // per tile, row-major: its block of kTileSize^2 levels
  std::vector<std::unique_ptr<uint8_t[]>> chunks_;  // the blocks, allocated a chunk at a time
  std::size_t last_chunk_blocks_ = 0;
  std::size_t blocks_in_last_chunk_ = 0;
  std::size_t allocated_blocks_ = 0;
  std::vector<const uint8_t*> uniform_block_;  // per level: the block shared by tiles of only that level
  std::size_t distinct_tiles_ = 0;
};

}  // namespace slamer

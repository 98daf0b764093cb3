#include "common/map/distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace slamer {
namespace {

constexpr int kTileCells = DistanceField::kTileSize * DistanceField::kTileSize;
constexpr std::size_t kMaxBlocksPerChunk = 64;

// One pass of the 1D squared distance transform over f[0..n), written to d.
// v (n) and z (n + 1) are scratch: parabola vertices and envelope boundaries.
void squared_distance_1d(const double* f, int n, double* d, int* v, double* z) {
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  for (int q = 1; q < n; ++q) {
    // Intersection of parabola q with the rightmost one kept; z[0] = -inf stops the loop.
    const auto intersection = [&](int p) {
      return ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) / (2.0 * (q - p));
    };
    double s = intersection(v[k]);
    while (s <= z[k]) {
      --k;
      s = intersection(v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) {
      ++k;
    }
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

DistanceField::TargetRows rows_of(const GridGeometry& geometry, const std::vector<uint8_t>& is_target) {
  if (is_target.size() != geometry.size()) {
    throw std::invalid_argument("distance field: target mask size differs from the grid");
  }
  return [&geometry, &is_target](int y, uint8_t* row) {
    std::copy_n(is_target.begin() + static_cast<std::ptrdiff_t>(geometry.index(0, y)), geometry.width, row);
  };
}

}  // namespace

DistanceField::DistanceField(const GridGeometry& geometry, const std::vector<uint8_t>& is_target, double max_distance)
    : DistanceField(geometry, rows_of(geometry, is_target), max_distance) {}

DistanceField::DistanceField(const GridGeometry& geometry, const TargetRows& targets, double max_distance)
    : geometry_(geometry), max_distance_(max_distance), step_(max_distance / kSaturated) {
  if (!(max_distance > 0.0) || !std::isfinite(max_distance)) {
    throw std::invalid_argument("distance field: max_distance must be > 0 and finite");
  }
  const int w = geometry.width;
  const int h = geometry.height;
  if (w <= 0 || h <= 0) {
    return;
  }
  tiles_x_ = (w + kTileSize - 1) / kTileSize;
  const int tiles_y = (h + kTileSize - 1) / kTileSize;
  tiles_.assign(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y), nullptr);
  uniform_block_.assign(kSaturated + 1, nullptr);

  // A column distance of `cap` cells or more puts a cell beyond max_distance,
  // so column distances are kept up to cap and a band needs cap rows of margin.
  const double max_cells = max_distance / geometry.resolution;
  const int cap = static_cast<int>(std::min(std::floor(max_cells) + 1.0, 65535.0));
  const auto wu = static_cast<std::size_t>(w);
  const int padded_width = tiles_x_ * kTileSize;
  std::vector<uint8_t> row(wu);
  std::vector<uint16_t> column((static_cast<std::size_t>(kTileSize) + 2 * static_cast<std::size_t>(cap)) * wu);
  std::vector<uint8_t> band(static_cast<std::size_t>(kTileSize) * static_cast<std::size_t>(padded_width));
  std::vector<double> f(wu);
  std::vector<double> d(wu);
  std::vector<int> v(wu);
  std::vector<double> z(wu + 1);
  const double max_squared_cells = max_cells * max_cells;

  for (int y0 = 0; y0 < h; y0 += kTileSize) {
    const int rows = std::min(kTileSize, h - y0);
    const int lo = std::max(0, y0 - cap);
    const int hi = std::min(h, y0 + rows + cap);
    // Columns: distance in cells along y to the nearest target within the window, capped.
    for (int r = 0; r < hi - lo; ++r) {
      targets(lo + r, row.data());
      uint16_t* g = &column[static_cast<std::size_t>(r) * wu];
      const uint16_t* below = r > 0 ? g - wu : nullptr;
      for (std::size_t x = 0; x < wu; ++x) {
        const int from_below = below != nullptr ? std::min(below[x] + 1, cap) : cap;
        g[x] = static_cast<uint16_t>(row[x] != 0 ? 0 : from_below);
        has_targets_ = has_targets_ || row[x] != 0;
      }
    }
    for (int r = hi - lo - 2; r >= 0; --r) {
      uint16_t* g = &column[static_cast<std::size_t>(r) * wu];
      const uint16_t* above = g + wu;
      for (std::size_t x = 0; x < wu; ++x) {
        g[x] = static_cast<uint16_t>(std::min<int>(g[x], above[x] + 1));
      }
    }
    // Rows: the exact squared distance in cells, quantized.
    std::fill(band.begin(), band.end(), static_cast<uint8_t>(kSaturated));
    for (int r = 0; r < rows; ++r) {
      const uint16_t* g = &column[static_cast<std::size_t>(y0 + r - lo) * wu];
      if (std::all_of(g, g + wu, [&](uint16_t c) { return c >= cap; })) {
        continue;  // nothing within reach of this row
      }
      for (std::size_t x = 0; x < wu; ++x) {
        f[x] = static_cast<double>(g[x]) * g[x];
      }
      squared_distance_1d(f.data(), w, d.data(), v.data(), z.data());
      uint8_t* out = &band[static_cast<std::size_t>(r) * static_cast<std::size_t>(padded_width)];
      for (std::size_t x = 0; x < wu; ++x) {
        out[x] = d[x] >= max_squared_cells
                     ? static_cast<uint8_t>(kSaturated)
                     : static_cast<uint8_t>(
                           std::min<long>(kSaturated, std::lround(std::sqrt(d[x]) * geometry.resolution / step_)));
      }
    }
    add_band(y0 / kTileSize, band, rows);
  }
}

uint8_t* DistanceField::new_block() {
  if (chunks_.empty() || blocks_in_last_chunk_ == last_chunk_blocks_) {
    // Chunks grow with the field (4, 4, 8, 16, ... 64 blocks) so a small map wastes little.
    last_chunk_blocks_ = std::clamp<std::size_t>(allocated_blocks_, 4, kMaxBlocksPerChunk);
    chunks_.push_back(std::make_unique<uint8_t[]>(last_chunk_blocks_ * kTileCells));
    allocated_blocks_ += last_chunk_blocks_;
    blocks_in_last_chunk_ = 0;
  }
  return chunks_.back().get() + (blocks_in_last_chunk_++) * kTileCells;
}

void DistanceField::add_band(int tile_row, const std::vector<uint8_t>& band, int rows) {
  const int padded_width = tiles_x_ * kTileSize;
  for (int tx = 0; tx < tiles_x_; ++tx) {
    const int columns = std::min(kTileSize, geometry_.width - tx * kTileSize);
    const uint8_t* corner = &band[static_cast<std::size_t>(tx) * kTileSize];
    const uint8_t first = corner[0];
    bool uniform = true;
    for (int r = 0; r < rows && uniform; ++r) {
      const uint8_t* line = corner + static_cast<std::ptrdiff_t>(r) * padded_width;
      uniform = std::all_of(line, line + columns, [&](uint8_t level) { return level == first; });
    }
    const uint8_t*& tile =
        tiles_[static_cast<std::size_t>(tile_row) * static_cast<std::size_t>(tiles_x_) + static_cast<std::size_t>(tx)];
    if (uniform) {
      if (uniform_block_[first] == nullptr) {
        uint8_t* block = new_block();
        std::fill_n(block, kTileCells, first);
        uniform_block_[first] = block;
      }
      tile = uniform_block_[first];
      continue;
    }
    uint8_t* block = new_block();
    for (int r = 0; r < kTileSize; ++r) {
      std::copy_n(corner + static_cast<std::ptrdiff_t>(r) * padded_width, kTileSize, block + r * kTileSize);
    }
    tile = block;
    ++distinct_tiles_;
  }
}

std::optional<float> DistanceField::at_world(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = geometry_.cell_at(world);
  if (!cell) {
    return std::nullopt;
  }
  return at(cell->x, cell->y);
}

std::size_t DistanceField::memory_bytes() const {
  return allocated_blocks_ * kTileCells + tiles_.size() * sizeof(const uint8_t*) +
         uniform_block_.size() * sizeof(const uint8_t*);
}

}  // namespace slamer

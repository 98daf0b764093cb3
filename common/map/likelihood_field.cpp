#include "common/map/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/map/placed_keys_avx2.hpp"

namespace slamer {
namespace {

void check(const LikelihoodFieldOptions& options) {
  const double weights = options.z_hit + options.z_max + options.z_rand;
  if (!(options.sigma_hit > 0.0) || !(options.range_max > 0.0) || !(options.z_rand > 0.0) || options.z_hit < 0.0 ||
      options.z_max < 0.0 || !(std::abs(weights - 1.0) <= 1e-6)) {
    throw std::invalid_argument(
        "likelihood field: need sigma_hit > 0, range_max > 0, z_rand > 0, z_hit + z_max + z_rand = 1");
  }
}

double hit_normalizer(const LikelihoodFieldOptions& options) {
  return options.z_hit / (std::sqrt(2.0 * std::numbers::pi) * options.sigma_hit);
}

}  // namespace

double likelihood_field_reach(const LikelihoodFieldOptions& options) {
  check(options);
  const double random = options.z_rand / options.range_max;
  const double ratio = hit_normalizer(options) / (1e-4 * random);
  return ratio > 1.0 ? options.sigma_hit * std::sqrt(2.0 * std::log(ratio)) : options.sigma_hit;
}

LikelihoodField::LikelihoodField(std::shared_ptr<const DistanceField> obstacles, const LikelihoodFieldOptions& options,
                                 std::size_t dense_cells_max, Vectorization vectorization)
    : distances_(std::move(obstacles)) {
  const double reach = likelihood_field_reach(options);
  if (distances_ == nullptr || distances_->max_distance() < reach) {
    throw std::invalid_argument("likelihood field: distances must reach " + std::to_string(reach) + " m");
  }
  const double random = options.z_rand / options.range_max;
  const double normalizer = hit_normalizer(options);
  const double inv_two_var = 1.0 / (2.0 * options.sigma_hit * options.sigma_hit);
  for (int level = 0; level <= DistanceField::kSaturated; ++level) {
    const double d = level * distances_->step();
    const double hit = level < DistanceField::kSaturated ? normalizer * std::exp(-d * d * inv_two_var) : 0.0;
    table_[static_cast<std::size_t>(level)] = static_cast<float>(std::log(hit + random));
  }
  off_map_ = static_cast<float>(std::log(random));
  // The saturated level's hit term is 0: its log-likelihood is the off-map one, to the bit.
  if (table_[DistanceField::kSaturated] != off_map_) {
    throw std::logic_error("likelihood field: the saturated level must score as off the map");
  }
  std::copy(table_.begin(), table_.end(), table_wide_.begin());
  max_range_ = static_cast<float>(std::log(options.z_max + random));
  const GridGeometry& g = geometry();
  // Dense keys are int32 cell indices, with one past the last for off the map.
  if (g.size() <= dense_cells_max && g.size() < std::size_t{std::numeric_limits<int32_t>::max()}) {
    // The cell past the last is saturated: off the map scores the same.
    auto levels = std::make_shared<std::vector<uint8_t>>(g.size() + 1, uint8_t{DistanceField::kSaturated});
    for (int y = 0; y < g.height; ++y) {
      for (int x = 0; x < g.width; ++x) {
        (*levels)[g.index(x, y)] = distances_->level(x, y);
      }
    }
    dense_levels_ = std::move(levels);
  }
  avx2_ = vectorization == Vectorization::kBest && placed_keys_avx2_available();
}

namespace {

// GCC's vector extensions (clang has them too): SSE2 on x86-64, NEON on arm64,
// plain scalar code elsewhere, with no intrinsics of one instruction set.
using Floats = float __attribute__((vector_size(16)));
using Ints = int32_t __attribute__((vector_size(16)));
constexpr std::size_t kLanes = 4;
constexpr std::size_t kBlock = 64;  // points placed before they are looked up
constexpr int kCellBits = 2 * DistanceField::kTileBits;
constexpr int32_t kOffMap = -1;

// The sum of sum_placed, with `key(cx, cy)` where a point falls (cells, on
// the grid; any non-negative int32 per cell), `off_key` off it and
// `term(key)` the log-likelihood. The points are placed a vector at a time,
// in the order the scalar code does it, so the cells are the same; then
// looked up one by one. `place_fast(i, count, keys)` may key points i, i + 1,
// ... of a block itself and returns how many it did (a multiple of kLanes);
// the rest are placed here.
template <class Key, class Term, class PlaceFast>
double sum_keyed(const LikelihoodField::Cells& f, const float* x, const float* y, std::size_t n, float c, float s,
                 float tx, float ty, const Key& key, int32_t off_key, const Term& term, const PlaceFast& place_fast) {
  const Floats vc = {c, c, c, c}, vs = {s, s, s, s}, vtx = {tx, tx, tx, tx}, vty = {ty, ty, ty, ty};
  const Floats width = {f.width, f.width, f.width, f.width}, height = {f.height, f.height, f.height, f.height};
  const Floats zero = {0.0f, 0.0f, 0.0f, 0.0f};
  // Four running sums, each in a register: one would make every lookup wait
  // for the previous addition.
  double sum0 = 0.0, sum1 = 0.0, sum2 = 0.0, sum3 = 0.0;
  int32_t keys[kBlock];
  std::size_t i = 0;
  while (i + kLanes <= n) {
    const std::size_t count = std::min(kBlock, (n - i) / kLanes * kLanes);
    for (std::size_t k = place_fast(i, count, keys); k < count; k += kLanes) {
      Floats px, py;
      std::memcpy(&px, x + i + k, sizeof px);
      std::memcpy(&py, y + i + k, sizeof py);
      const Floats gx = vc * px - vs * py + vtx;
      const Floats gy = vs * px + vc * py + vty;
      const Ints inside = (gx >= zero) & (gy >= zero) & (gx < width) & (gy < height);
      // Off the grid the coordinates may be anything: converted only where inside.
      const Ints cx = __builtin_convertvector(reinterpret_cast<Floats>(reinterpret_cast<Ints>(gx) & inside), Ints);
      const Ints cy = __builtin_convertvector(reinterpret_cast<Floats>(reinterpret_cast<Ints>(gy) & inside), Ints);
      const Ints masked = (key(cx, cy) & inside) | (~inside & off_key);
      std::memcpy(keys + k, &masked, sizeof masked);
    }
    for (std::size_t k = 0; k < count; k += kLanes) {
      sum0 += term(keys[k]);
      sum1 += term(keys[k + 1]);
      sum2 += term(keys[k + 2]);
      sum3 += term(keys[k + 3]);
    }
    i += count;
  }
  for (; i < n; ++i) {
    sum0 += f(c * x[i] - s * y[i] + tx, s * x[i] + c * y[i] + ty);
  }
  return (sum0 + sum1) + (sum2 + sum3);
}

}  // namespace

double LikelihoodField::sum_placed(const float* x, const float* y, std::size_t n, float c, float s, float tx,
                                   float ty) const {
  const Cells f = cells();
  if (dense_levels_) {
    const int32_t width = geometry().width;
    const uint8_t* levels = dense_levels_->data();
    // Off the grid: the cell past the last, at the saturated level, whose
    // log-likelihood is the off-map one (no branch per point).
    const auto off_key = static_cast<int32_t>(geometry().size());
    const auto place_fast = [&](std::size_t i, std::size_t count, int32_t* keys) {
      return avx2_ ? place_dense_keys_avx2(x + i, y + i, count, c, s, tx, ty, width, f.width, f.height, off_key, keys)
                   : std::size_t{0};
    };
    return sum_keyed(
        f, x, y, n, c, s, tx, ty, [&](const Ints& cx, const Ints& cy) { return cy * width + cx; }, off_key,
        [&](int32_t key) { return table_wide_[levels[key]]; }, place_fast);
  }
  // A tile's index and the cell within it in one key (tile << kCellBits | cell):
  // up to 2^(31 - kCellBits) tiles, a map of 2^31 cells (2.3 km square at
  // 5 cm); a larger one is summed point by point.
  constexpr int kBits = DistanceField::kTileBits;
  constexpr int32_t kMask = DistanceField::kTileSize - 1;
  const std::size_t tiles_y = (static_cast<std::size_t>(geometry().height) + kMask) >> kBits;
  if (f.levels.tiles_x * tiles_y >= (std::size_t{1} << (31 - kCellBits))) {
    return sum_terms(n, [&](std::size_t i) { return f(c * x[i] - s * y[i] + tx, s * x[i] + c * y[i] + ty); });
  }
  const int32_t tiles_x = static_cast<int32_t>(f.levels.tiles_x);
  return sum_keyed(
      f, x, y, n, c, s, tx, ty,
      [&](const Ints& cx, const Ints& cy) {
        return (((cy >> kBits) * tiles_x + (cx >> kBits)) << kCellBits) | ((cy & kMask) << kBits) | (cx & kMask);
      },
      kOffMap,
      [&](int32_t key) {
        return key == kOffMap ? f.off_map : table_wide_[f.levels.tiles[key >> kCellBits][key & ((1 << kCellBits) - 1)]];
      },
      [](std::size_t, std::size_t, int32_t*) { return std::size_t{0}; });
}

LikelihoodField::CellScan LikelihoodField::place_cells(const float* x, const float* y, std::size_t n, float c, float s,
                                                       float tx, float ty) const {
  // Far off the grid a cell only has to stay off it under any shift a search
  // makes, and its int32 arithmetic must not overflow.
  constexpr float kFar = 16777216.0f;  // 2^24
  const auto cell = [&](float g) {
    return g >= -kFar && g <= kFar ? static_cast<int32_t>(std::floor(g)) : static_cast<int32_t>(-kFar);
  };
  CellScan scan;
  scan.x.resize(n);
  scan.y.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    scan.x[i] = cell(c * x[i] - s * y[i] + tx);
    scan.y[i] = cell(s * x[i] + c * y[i] + ty);
  }
  if (n == 0) {
    return scan;
  }
  const auto [min_x, max_x] = std::minmax_element(scan.x.begin(), scan.x.end());
  const auto [min_y, max_y] = std::minmax_element(scan.y.begin(), scan.y.end());
  scan.min_x = *min_x;
  scan.max_x = *max_x;
  scan.min_y = *min_y;
  scan.max_y = *max_y;
  const int64_t width = geometry().width;
  // Keys where every one is an int32 (a key plus a shift that puts its cell on
  // the grid is then one too).
  const auto fits = [](int64_t key) {
    return key >= std::numeric_limits<int32_t>::min() && key <= std::numeric_limits<int32_t>::max();
  };
  if (dense_levels_ && fits(scan.min_y * width + scan.min_x) && fits(scan.max_y * width + scan.max_x)) {
    scan.keys.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      scan.keys[i] = static_cast<int32_t>(scan.y[i] * width + scan.x[i]);
    }
  }
  return scan;
}

double LikelihoodField::sum_shifted(const CellScan& scan, int32_t dx, int32_t dy) const {
  const Cells f = cells();
  const int64_t width = geometry().width;
  const int64_t height = geometry().height;
  const bool on_grid = int64_t{scan.min_x} + dx >= 0 && int64_t{scan.max_x} + dx < width &&
                       int64_t{scan.min_y} + dy >= 0 && int64_t{scan.max_y} + dy < height;
  const int64_t shift = dy * width + dx;
  if (on_grid && !scan.keys.empty() && shift >= std::numeric_limits<int32_t>::min() &&
      shift <= std::numeric_limits<int32_t>::max()) {
    const int32_t* keys = scan.keys.data();
    const uint8_t* levels = dense_levels_->data();
    const auto offset = static_cast<int32_t>(shift);
    return sum_terms(scan.keys.size(), [&](std::size_t i) { return table_wide_[levels[keys[i] + offset]]; });
  }
  // Point by point, off the grid at the off-map value; a dense field's cells in one load.
  const auto sum_checked = [&](const auto& level_at) {
    return sum_terms(scan.x.size(), [&](std::size_t i) {
      const int64_t cx = int64_t{scan.x[i]} + dx;
      const int64_t cy = int64_t{scan.y[i]} + dy;
      // Unsigned: a negative cell compares as huge, two tests instead of four.
      return static_cast<uint64_t>(cx) < static_cast<uint64_t>(width) &&
                     static_cast<uint64_t>(cy) < static_cast<uint64_t>(height)
                 ? table_wide_[level_at(cx, cy)]
                 : double{f.off_map};
    });
  };
  if (dense_levels_) {
    const uint8_t* levels = dense_levels_->data();
    return sum_checked([&](int64_t cx, int64_t cy) { return levels[cy * width + cx]; });
  }
  return sum_checked([&](int64_t cx, int64_t cy) { return f.levels(static_cast<int>(cx), static_cast<int>(cy)); });
}

float LikelihoodField::log_likelihood_at(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = geometry().cell_at(world);
  return cell ? log_likelihood(cell->x, cell->y) : off_map_;
}

}  // namespace slamer

#include "common/map/distance_field.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {
namespace {

constexpr double kFar = 1e20;  // "no target": larger than any squared distance on a map

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

}  // namespace

DistanceField::DistanceField(const GridGeometry& geometry, const std::vector<uint8_t>& is_target)
    : geometry_(geometry), distance_(geometry.size(), std::numeric_limits<float>::infinity()) {
  const int w = geometry.width;
  const int h = geometry.height;
  has_targets_ = std::any_of(is_target.begin(), is_target.end(), [](uint8_t t) { return t != 0; });
  if (!has_targets_ || w <= 0 || h <= 0) {
    return;
  }
  const int longest = std::max(w, h);
  std::vector<double> f(static_cast<std::size_t>(longest));
  std::vector<double> d(static_cast<std::size_t>(longest));
  std::vector<int> v(static_cast<std::size_t>(longest));
  std::vector<double> z(static_cast<std::size_t>(longest) + 1);
  std::vector<double> squared(geometry.size());

  // Columns: squared distance along y to the nearest target in the same column.
  for (int x = 0; x < w; ++x) {
    for (int y = 0; y < h; ++y) {
      f[static_cast<std::size_t>(y)] = is_target[geometry.index(x, y)] != 0 ? 0.0 : kFar;
    }
    squared_distance_1d(f.data(), h, d.data(), v.data(), z.data());
    for (int y = 0; y < h; ++y) {
      squared[geometry.index(x, y)] = d[static_cast<std::size_t>(y)];
    }
  }
  // Rows: combine, giving the exact squared Euclidean distance in cells.
  const double resolution = geometry.resolution;
  for (int y = 0; y < h; ++y) {
    std::copy_n(squared.begin() + static_cast<std::ptrdiff_t>(geometry.index(0, y)), w, f.begin());
    squared_distance_1d(f.data(), w, d.data(), v.data(), z.data());
    for (int x = 0; x < w; ++x) {
      distance_[geometry.index(x, y)] = static_cast<float>(std::sqrt(d[static_cast<std::size_t>(x)]) * resolution);
    }
  }
}

std::optional<float> DistanceField::at_world(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = geometry_.cell_at(world);
  if (!cell) {
    return std::nullopt;
  }
  return at(cell->x, cell->y);
}

}  // namespace slamer

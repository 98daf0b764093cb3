// The LFM likelihood field (common/map/likelihood_field.hpp): its table by
// hand, and its sums of placed points and of shifted cells against the
// point-by-point definition, tiled and dense, on and off the map.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "common/map/distance_field.hpp"
#include "common/map/likelihood_field.hpp"

namespace slamer {
namespace {

TEST(LikelihoodField, HandComputedValues) {
  GridGeometry g{3, 1, 1.0, {}};
  // 5.1 m in 255 levels: 0.02 m a level, so 1 m and 2 m are exact levels.
  const auto obstacles = std::make_shared<const DistanceField>(g, std::vector<uint8_t>{1, 0, 0}, 5.1);
  LikelihoodFieldOptions options;
  options.sigma_hit = 0.5;
  options.z_hit = 0.8;
  options.z_max = 0.1;
  options.z_rand = 0.1;
  options.range_max = 20.0;
  const LikelihoodField field(obstacles, options);
  const double norm = 0.8 / (std::sqrt(2.0 * std::numbers::pi) * 0.5);
  EXPECT_NEAR(field.log_likelihood(0, 0), std::log(norm + 0.1 / 20.0), 1e-6);
  EXPECT_NEAR(field.log_likelihood(2, 0), std::log(norm * std::exp(-4.0 / (2 * 0.25)) + 0.1 / 20.0), 1e-6);
  EXPECT_NEAR(field.off_map_log_likelihood(), std::log(0.1 / 20.0), 1e-6);
  EXPECT_NEAR(field.max_range_log_likelihood(), std::log(0.1 + 0.1 / 20.0), 1e-6);
  EXPECT_NEAR(field.log_likelihood_at({-3.0, 0.5}), field.off_map_log_likelihood(), 1e-9);
  // Reach: the hit term falls to 1e-4 of the random term, sigma * sqrt(2 ln(norm / (1e-4 * random))).
  const double reach = 0.5 * std::sqrt(2.0 * std::log(norm / (1e-4 * 0.1 / 20.0)));
  EXPECT_NEAR(likelihood_field_reach(options), reach, 1e-9);
  EXPECT_NEAR(reach, 2.65, 0.01);
  const auto short_reach = std::make_shared<const DistanceField>(g, std::vector<uint8_t>{1, 0, 0}, 2.0);
  EXPECT_THROW(LikelihoodField(short_reach, options), std::invalid_argument);
  options.z_rand = 0.3;  // weights sum to 1.2
  EXPECT_THROW(LikelihoodField(obstacles, options), std::invalid_argument);
}

// One likelihood field, tiled and dense, over 60 obstacle cells drawn from
// `rng` in 100 x 70 cells: tiles cut at 32 in both axes, a partial tile at
// each far edge.
struct TiledAndDense {
  GridGeometry g{100, 70, 0.05, {}};
  std::shared_ptr<const DistanceField> distances;
  LikelihoodField tiled, dense;
  LikelihoodField dense_portable;  // dense, never with AVX2
};
TiledAndDense scattered_obstacles(std::mt19937& rng) {
  const GridGeometry g{100, 70, 0.05, {}};
  std::vector<uint8_t> targets(g.size(), 0);
  std::uniform_int_distribution<std::size_t> any_cell(0, g.size() - 1);
  for (int k = 0; k < 60; ++k) {
    targets[any_cell(rng)] = 1;
  }
  const auto distances = std::make_shared<const DistanceField>(g, targets, 1.5);
  return {g, distances, LikelihoodField(distances, LikelihoodFieldOptions{}),
          LikelihoodField(distances, LikelihoodFieldOptions{}, g.size()),
          LikelihoodField(distances, LikelihoodFieldOptions{}, g.size(), LikelihoodField::Vectorization::kPortable)};
}

TEST(LikelihoodField, SumOfPlacedPointsIsTheSumOfTheirCellsOnAndOffTheMapTiledOrDense) {
  std::mt19937 rng(7);
  const auto [g, distances, field, dense, dense_portable] = scattered_obstacles(rng);
  EXPECT_EQ(field.dense_bytes(), 0u);
  EXPECT_EQ(dense.dense_bytes(), g.size() + 1);  // and the off-map cell
  EXPECT_EQ(LikelihoodField(distances, LikelihoodFieldOptions{}, g.size() - 1).dense_bytes(), 0u);
  const LikelihoodField::Cells cells = field.cells();
  // Points reaching 30 cells beyond every edge, and a few on the edges themselves.
  std::uniform_real_distribution<float> coordinate(-80.0f, 80.0f);
  std::vector<float> x, y;
  for (int k = 0; k < 203; ++k) {
    x.push_back(coordinate(rng));
    y.push_back(coordinate(rng));
  }
  const float edges[][2] = {{0.0f, 0.0f},       {-0.0f, 5.0f}, {100.0f, 5.0f},
                            {99.999f, 69.999f}, {5.0f, 70.0f}, {std::nanf(""), 3.0f}};
  for (std::size_t k = 0; k < std::size(edges); ++k) {
    x[20 + 7 * k] = edges[k][0];
    y[20 + 7 * k] = edges[k][1];
  }
  int off_map = 0;
  for (const auto& [c, s, tx, ty] : {std::array<float, 4>{1.0f, 0.0f, 0.0f, 0.0f},
                                     {std::cos(0.7f), std::sin(0.7f), 50.0f, 35.0f},
                                     {std::cos(-2.9f), std::sin(-2.9f), 12.5f, 60.25f}}) {
    // Lengths around the vector width (4) and the block (64), and one that is neither.
    for (const std::size_t n : {0, 3, 4, 63, 64, 65, 68, 203}) {
      double expected = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const float gx = c * x[i] - s * y[i] + tx;
        const float gy = s * x[i] + c * y[i] + ty;
        const bool on_map = gx >= 0.0f && gy >= 0.0f && gx < 100.0f && gy < 70.0f;
        off_map += on_map ? 0 : 1;
        expected +=
            on_map ? field.log_likelihood(static_cast<int>(gx), static_cast<int>(gy)) : field.off_map_log_likelihood();
        EXPECT_EQ(cells(gx, gy), on_map ? field.log_likelihood(static_cast<int>(gx), static_cast<int>(gy))
                                        : field.off_map_log_likelihood());
      }
      EXPECT_NEAR(field.sum_placed(x.data(), y.data(), n, c, s, tx, ty), expected, 1e-9) << n << " points";
      EXPECT_NEAR(dense.sum_placed(x.data(), y.data(), n, c, s, tx, ty), expected, 1e-9) << n << " points, dense";
      EXPECT_NEAR(dense_portable.sum_placed(x.data(), y.data(), n, c, s, tx, ty), expected, 1e-9) << n << " points";
    }
  }
  EXPECT_GT(off_map, 100);  // both branches are exercised
}

// The AVX2 placing (placed_keys_avx2.hpp) rounds as the portable code does, so
// a beam's cell and the sum are the same to the bit: at every length from 0
// to 140 (eight at a time, four, one) for points on the map's edges, and at
// 5000 poses that each put a point on a cell's corner.
TEST(LikelihoodField, AvxSumsAreThePortableSumsToTheBit) {
  std::mt19937 rng(11);
  const auto [g, distances, tiled, dense, dense_portable] = scattered_obstacles(rng);
  EXPECT_FALSE(tiled.sums_with_avx2());
  EXPECT_FALSE(dense_portable.sums_with_avx2());
  if (!dense.sums_with_avx2()) {
    GTEST_SKIP() << "this machine has no AVX2: the portable code is the only one";
  }
  std::uniform_real_distribution<float> coordinate(-80.0f, 80.0f);
  std::vector<float> x, y;
  for (int k = 0; k < 140; ++k) {
    x.push_back(coordinate(rng));
    y.push_back(coordinate(rng));
  }
  // Unrotated and untranslated, these land on the edges of the map and of its cells.
  const float edges[][2] = {{0.0f, 0.0f},          {-0.0f, 3.0f},
                            {99.0f, 0.0f},         {100.0f, 5.0f},
                            {5.0f, 69.0f},         {5.0f, 70.0f},
                            {-1e-7f, 5.0f},        {1e-7f, 6.0f},
                            {50.0f, 35.0f},        {3.0f, -0.0f},
                            {0.0f, 69.0f},         {99.999f, 69.999f},
                            {std::nanf(""), 1.0f}, {2.0f, std::numeric_limits<float>::infinity()}};
  for (std::size_t k = 0; k < std::size(edges); ++k) {
    x[3 + 9 * k] = edges[k][0];
    y[3 + 9 * k] = edges[k][1];
  }
  const auto same = [&](std::size_t n, float a, float tx, float ty) {
    const float c = a == 0.0f ? 1.0f : std::cos(a), s = a == 0.0f ? 0.0f : std::sin(a);
    return dense.sum_placed(x.data(), y.data(), n, c, s, tx, ty) ==
           dense_portable.sum_placed(x.data(), y.data(), n, c, s, tx, ty);
  };
  std::size_t differing = 0;
  for (std::size_t n = 0; n <= x.size(); ++n) {
    differing += same(n, 0.0f, 0.0f, 0.0f) ? 0 : 1;
  }
  EXPECT_EQ(differing, 0u) << "of 141 sums on the edges";
  // Each pose puts one point (as the portable code rounds it) exactly on a
  // cell's corner: a fused multiply-add, rounding once, lands beside it.
  std::uniform_real_distribution<float> heading(-3.2f, 3.2f);
  std::uniform_int_distribution<int> corner(1, 68);
  for (int pose = 0; pose < 5000; ++pose) {
    const float a = heading(rng);
    const std::size_t i = static_cast<std::size_t>(pose) % x.size();
    const float rotated_x = std::cos(a) * x[i] - std::sin(a) * y[i];
    const float rotated_y = std::sin(a) * x[i] + std::cos(a) * y[i];
    differing +=
        same(x.size(), a, static_cast<float>(corner(rng)) - rotated_x, static_cast<float>(corner(rng)) - rotated_y) ? 0
                                                                                                                    : 1;
  }
  EXPECT_EQ(differing, 0u) << "of 5000 sums with a point on a cell's corner";
}

TEST(LikelihoodField, PlacedCellsShiftedByWholeCellsSumAsThePointsPlacedThereTiledOrDense) {
  std::mt19937 rng(11);
  const auto [g, distances, tiled, dense, dense_portable] = scattered_obstacles(rng);
  const float c = std::cos(0.7f), s = std::sin(0.7f), tx = 50.25f, ty = 35.5f;
  // Points that land at least 0.01 cell from a cell's edge, so that a float's
  // rounding cannot tell placing then shifting from placing there; a scan
  // within 20 cells of the centre, and one reaching 30 cells beyond every edge.
  const auto clear_of_edges = [&](float x, float y) {
    const float gx = c * x - s * y + tx, gy = s * x + c * y + ty;
    return std::abs(gx - std::round(gx)) > 0.01f && std::abs(gy - std::round(gy)) > 0.01f;
  };
  const auto points = [&](float reach) {
    std::uniform_real_distribution<float> coordinate(-reach, reach);
    std::vector<float> x, y;
    while (x.size() < 150) {
      const float px = coordinate(rng), py = coordinate(rng);
      if (clear_of_edges(px, py)) {
        x.push_back(px);
        y.push_back(py);
      }
    }
    return std::pair{x, y};
  };
  int fast = 0, checked = 0;
  for (const auto& [x, y] : {points(20.0f), points(80.0f)}) {
    for (const LikelihoodField* field : {&tiled, &dense}) {
      const LikelihoodField::CellScan scan = field->place_cells(x.data(), y.data(), x.size(), c, s, tx, ty);
      ASSERT_EQ(scan.x.size(), x.size());
      for (const int dy : {-31, -6, 0, 4, 30}) {
        for (const int dx : {-45, -7, 0, 2, 44}) {
          const double expected = field->sum_placed(x.data(), y.data(), x.size(), c, s, tx + static_cast<float>(dx),
                                                    ty + static_cast<float>(dy));
          EXPECT_NEAR(field->sum_shifted(scan, dx, dy), expected, 1e-9) << dx << ", " << dy;
          const bool on_grid =
              scan.min_x + dx >= 0 && scan.max_x + dx < g.width && scan.min_y + dy >= 0 && scan.max_y + dy < g.height;
          (on_grid && !scan.keys.empty() ? fast : checked) += 1;
        }
      }
    }
  }
  EXPECT_GT(fast, 5);  // the dense fast path and the checked paths are both exercised
  EXPECT_GT(checked, 50);
  // A point far off (or NaN) stays off the grid under any shift; no points sum to 0.
  const float far_x[] = {1e9f, std::nanf(""), 10.0f}, far_y[] = {0.0f, 0.0f, 1e9f};
  const LikelihoodField::CellScan far = dense.place_cells(far_x, far_y, 3, 1.0f, 0.0f, 0.0f, 0.0f);
  for (const int shift : {0, 1000000}) {
    EXPECT_DOUBLE_EQ(dense.sum_shifted(far, shift, shift), 3.0 * dense.off_map_log_likelihood());
    EXPECT_DOUBLE_EQ(tiled.sum_shifted(far, -shift, 0), 3.0 * tiled.off_map_log_likelihood());
  }
  EXPECT_EQ(dense.sum_shifted(dense.place_cells(far_x, far_y, 0, c, s, tx, ty), 3, 4), 0.0);
}

}  // namespace
}  // namespace slamer

#include "common/stats/rolling_percentiles.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace slamer {
namespace {

TEST(RollingPercentiles, EmptyIsZero) {
  const RollingPercentiles p(10);
  EXPECT_EQ(p.size(), 0u);
  EXPECT_EQ(p.percentile(0.5), 0.0);
}

TEST(RollingPercentiles, NearestRankOnOneToHundred) {
  RollingPercentiles p(100);
  for (int i = 100; i >= 1; --i) {
    p.add(i);
  }
  EXPECT_DOUBLE_EQ(p.percentile(0.5), 50.0);
  EXPECT_DOUBLE_EQ(p.percentile(0.99), 99.0);
  EXPECT_DOUBLE_EQ(p.percentile(1.0), 100.0);
  EXPECT_DOUBLE_EQ(p.percentile(0.0), 1.0);
}

TEST(RollingPercentiles, KeepsOnlyTheWindow) {
  RollingPercentiles p(10);
  for (int i = 0; i < 10; ++i) {
    p.add(1000.0);
  }
  for (int i = 0; i < 10; ++i) {
    p.add(1.0);  // pushes every 1000 out
  }
  EXPECT_EQ(p.size(), 10u);
  EXPECT_DOUBLE_EQ(p.percentile(1.0), 1.0);
}

TEST(RollingPercentiles, IgnoresNonFinite) {
  RollingPercentiles p(10);
  p.add(std::numeric_limits<double>::quiet_NaN());
  p.add(std::numeric_limits<double>::infinity());
  p.add(2.0);
  EXPECT_EQ(p.size(), 1u);
  EXPECT_DOUBLE_EQ(p.percentile(0.99), 2.0);
}

}  // namespace
}  // namespace slamer

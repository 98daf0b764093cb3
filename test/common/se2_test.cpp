#include "common/geometry/se2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace slamer {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_pose_near(const Pose2& actual, const Pose2& expected, double tolerance = 1e-12) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(angle_diff(actual.theta, expected.theta), 0.0, tolerance);
}

Pose2 random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> position(-50.0, 50.0);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  return {position(rng), position(rng), angle(rng)};
}

TEST(WrapAngle, MapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);  // -pi is outside (-pi, pi]
  EXPECT_NEAR(wrap_angle(3.0 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-3.0 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(2.0 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_NEAR(wrap_angle(-2.0 * kPi - 0.25), -0.25, 1e-12);
  EXPECT_NEAR(wrap_angle(1e6), std::remainder(1e6, 2.0 * kPi), 1e-9);
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::infinity())));
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(WrapAngle, AlwaysInRangeForRandomInput) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-1e4, 1e4);
  for (int i = 0; i < 10000; ++i) {
    const double a = any(rng);
    const double w = wrap_angle(a);
    ASSERT_GT(w, -kPi);
    ASSERT_LE(w, kPi);
    ASSERT_NEAR(std::sin(w), std::sin(a), 1e-9);
    ASSERT_NEAR(std::cos(w), std::cos(a), 1e-9);
  }
}

TEST(AngleDiff, TakesTheShortWayAcrossPi) {
  EXPECT_NEAR(angle_diff(kPi - 0.1, -kPi + 0.1), -0.2, 1e-12);
  EXPECT_NEAR(angle_diff(-kPi + 0.1, kPi - 0.1), 0.2, 1e-12);
  EXPECT_NEAR(angle_diff(0.3, 0.1), 0.2, 1e-12);
}

TEST(Se2, ComposeMatchesHomogeneousMatrices) {
  std::mt19937 rng(1);
  for (int i = 0; i < 1000; ++i) {
    const Pose2 a = random_pose(rng);
    const Pose2 b = random_pose(rng);
    expect_pose_near(compose(a, b), from_matrix(to_matrix(a) * to_matrix(b)), 1e-9);
  }
}

TEST(Se2, HandComputedComposition) {
  // Robot at (1, 2) facing +y; a point 1 m ahead of it is at (1, 3).
  const Pose2 robot{1.0, 2.0, kPi / 2};
  expect_pose_near(compose(robot, {1.0, 0.0, 0.0}), {1.0, 3.0, kPi / 2});
  const Eigen::Vector2d p = transform_point(robot, {1.0, 0.5});
  EXPECT_NEAR(p.x(), 0.5, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Se2, InverseAndBetween) {
  std::mt19937 rng(2);
  for (int i = 0; i < 1000; ++i) {
    const Pose2 a = random_pose(rng);
    const Pose2 b = random_pose(rng);
    expect_pose_near(compose(a, inverse(a)), {}, 1e-9);
    expect_pose_near(compose(inverse(a), a), {}, 1e-9);
    expect_pose_near(compose(a, between(a, b)), b, 1e-9);
  }
}

TEST(Se2, ExpLogRoundTrip) {
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Pose2 a = random_pose(rng);
    expect_pose_near(exp_se2(log_se2(a)), a, 1e-9);
  }
  // Tiny rotations use the series and must agree with the exact formula's limit.
  const Pose2 straight = exp_se2({2.0, 0.0, 1e-9});
  EXPECT_NEAR(straight.x, 2.0, 1e-12);
  EXPECT_NEAR(straight.y, 1e-9, 1e-12);
}

TEST(Se2, ExpOfConstantTwistIsACircularArc) {
  // v = 1 m/s, omega = pi/2 rad/s for 1 s: a quarter circle of radius 2/pi.
  const double r = 2.0 / kPi;
  expect_pose_near(exp_se2({1.0, 0.0, kPi / 2}), {r, r, kPi / 2}, 1e-12);
}

TEST(Se2, InterpolateFollowsTheArc) {
  const Pose2 start{1.0, -1.0, 0.3};
  const Twist2 twist{1.0, 0.0, kPi / 2};
  const Pose2 end = compose(start, exp_se2(twist));
  expect_pose_near(interpolate(start, end, 0.0), start, 1e-12);
  expect_pose_near(interpolate(start, end, 1.0), end, 1e-12);
  // Halfway along a constant twist is the half twist, on the circle, not the chord.
  expect_pose_near(interpolate(start, end, 0.5), compose(start, exp_se2({0.5, 0.0, kPi / 4})), 1e-12);
  expect_pose_near(interpolate(start, end, 2.0), compose(end, exp_se2(twist)), 1e-9);
}

TEST(Se2, InterpolateTurnsTheShortWay) {
  const Pose2 a{0.0, 0.0, kPi - 0.1};
  const Pose2 b{0.0, 0.0, -kPi + 0.1};
  EXPECT_NEAR(std::abs(interpolate(a, b, 0.5).theta), kPi, 1e-12);
}

TEST(DistanceToSegment, PerpendicularInsideNearestEndOutside) {
  const Eigen::Vector2d a(1.0, 1.0);
  const Eigen::Vector2d b(3.0, 3.0);
  EXPECT_NEAR(distance_to_segment({3.0, 1.0}, a, b), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(distance_to_segment({4.0, 4.0}, a, b), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(distance_to_segment({0.0, 1.0}, a, b), 1.0, 1e-12);
  EXPECT_NEAR(distance_to_segment({2.0, 2.0}, a, b), 0.0, 1e-12);
  EXPECT_NEAR(distance_to_segment({5.0, 1.0}, a, a), 4.0, 1e-12);  // a point segment
}

TEST(CircularMean, HandlesWrapAround) {
  const std::vector<double> angles{kPi - 0.1, -kPi + 0.1};
  const auto mean = circular_mean(angles);
  ASSERT_TRUE(mean.has_value());
  EXPECT_NEAR(std::abs(*mean), kPi, 1e-12);  // not 0, as an arithmetic mean would say
}

TEST(CircularMean, Weighted) {
  const std::vector<double> angles{0.0, kPi / 2};
  const std::vector<double> weights{3.0, 1.0};
  const auto mean = circular_mean(angles, weights);
  ASSERT_TRUE(mean.has_value());
  EXPECT_NEAR(*mean, std::atan2(1.0, 3.0), 1e-12);
}

TEST(CircularMean, UndefinedCasesGiveNullopt) {
  EXPECT_FALSE(circular_mean({}).has_value());
  const std::vector<double> opposite{0.0, kPi};
  EXPECT_FALSE(circular_mean(opposite).has_value());
  const std::vector<double> two{0.1, 0.2};
  const std::vector<double> one_weight{1.0};
  EXPECT_FALSE(circular_mean(two, one_weight).has_value());
  const std::vector<double> negative{1.0, -1.0};
  EXPECT_FALSE(circular_mean(two, negative).has_value());
  const std::vector<double> zero{0.0, 0.0};
  EXPECT_FALSE(circular_mean(two, zero).has_value());
  const std::vector<double> with_nan{0.1, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_FALSE(circular_mean(with_nan).has_value());
}

}  // namespace
}  // namespace slamer

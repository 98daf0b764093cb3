#include "common/robot/diff_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace slamer {
namespace {

TEST(DiffDrive, TicksToTravelUsesGearAndCounts) {
  const DiffDriveOptions base;  // i-Cart mini: 400 counts x 75 gear, r = 0.07455 m
  EXPECT_DOUBLE_EQ(base.ticks_per_wheel_rev(), 30000.0);
  EXPECT_NEAR(wheel_travel(30000.0, base.wheel_radius_left, base), 2.0 * std::numbers::pi * 0.07455, 1e-12);
  EXPECT_NEAR(travel_ticks(wheel_travel(1234.0, 0.07, base), 0.07, base), 1234.0, 1e-9);
}

TEST(DiffDriveOdometry, StraightLineAndTurnOnTheSpot) {
  DiffDriveOptions base;
  DiffDriveOdometry odometry(base);
  EXPECT_TRUE(odometry.update(0, 0, 0));
  const auto ticks = static_cast<int64_t>(std::llround(travel_ticks(1.0, base.wheel_radius_left, base)));
  EXPECT_TRUE(odometry.update(1'000'000, ticks, ticks));
  EXPECT_NEAR(odometry.pose().x, 1.0, 1e-4);
  EXPECT_NEAR(odometry.pose().y, 0.0, 1e-12);
  EXPECT_NEAR(odometry.speed(), 1.0, 1e-4);
  // Quarter turn on the spot: each wheel travels tread * pi / 4.
  const auto turn = static_cast<int64_t>(
      std::llround(travel_ticks(base.tread * std::numbers::pi / 4.0, base.wheel_radius_left, base)));
  EXPECT_TRUE(odometry.update(2'000'000, ticks - turn, ticks + turn));
  EXPECT_NEAR(odometry.pose().theta, std::numbers::pi / 2.0, 1e-4);
  EXPECT_NEAR(odometry.pose().x, 1.0, 1e-4);
  EXPECT_NEAR(odometry.yaw_rate(), std::numbers::pi / 2.0, 1e-4);
}

TEST(DiffDriveOdometry, ArcIsIntegratedExactly) {
  // Wheels on a circle of radius R for a quarter turn: the pose ends at (R, R, pi/2)
  // in one update, which an Euler step would miss by ~0.2 R.
  DiffDriveOptions base;
  base.counts_per_motor_rev = 100000;  // fine ticks so rounding does not matter
  DiffDriveOdometry odometry(base);
  odometry.update(0, 0, 0);
  const double radius = 2.0;
  const double left = (radius - base.tread / 2) * std::numbers::pi / 2;
  const double right = (radius + base.tread / 2) * std::numbers::pi / 2;
  odometry.update(1'000'000, std::llround(travel_ticks(left, base.wheel_radius_left, base)),
                  std::llround(travel_ticks(right, base.wheel_radius_right, base)));
  EXPECT_NEAR(odometry.pose().x, radius, 1e-5);
  EXPECT_NEAR(odometry.pose().y, radius, 1e-5);
  EXPECT_NEAR(odometry.pose().theta, std::numbers::pi / 2, 1e-6);
}

TEST(DiffDriveOdometry, TimeGoingBackwardsIsIgnored) {
  DiffDriveOdometry odometry{DiffDriveOptions{}};
  odometry.update(5'000'000, 0, 0);
  EXPECT_FALSE(odometry.update(4'000'000, 1000, 1000));
  EXPECT_FALSE(odometry.update(5'000'000, 1000, 1000));
  EXPECT_DOUBLE_EQ(odometry.pose().x, 0.0);
  odometry.reset({1.0, 2.0, 0.5});
  EXPECT_TRUE(odometry.update(1'000, 0, 0));
  EXPECT_DOUBLE_EQ(odometry.pose().y, 2.0);
}

}  // namespace
}  // namespace slamer

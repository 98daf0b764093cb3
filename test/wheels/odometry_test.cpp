// Tick unwrapping, exact-arc vs first-order integration, and frame timestamps.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/wheels/wheel_odometry.hpp"

namespace slamer::tfrog {
namespace {

Kinematics icart() {
  Kinematics k;
  k.radius = {0.07455, -0.07455};
  k.tread = 0.30737;
  k.counts_per_wheel_rev = {30000.0, 30000.0};
  k.cycle = 0.001;
  k.max_vel = 0.9;
  k.max_w = 3.14;
  k.max_acc_v = 1.5;
  k.max_acc_w = 6.28;
  return k;
}

TEST(TickUnwrapper, WrapsAndRebases) {
  TickUnwrapper u;
  EXPECT_EQ(u.feed({32000, -32000}), (std::array<int64_t, 2>{0, 0}));         // first frame anchors
  EXPECT_EQ(u.feed({-32536, 32536}), (std::array<int64_t, 2>{1000, -1000}));  // across the int16 wrap
  EXPECT_EQ(u.cumulative(), (std::array<int64_t, 2>{1000, -1000}));
  // The board restarted (replug): counts begin again at 0 and continue.
  u.rebase(std::array<int16_t, 2>{0, 0});
  EXPECT_EQ(u.feed({25, -25}), (std::array<int64_t, 2>{25, -25}));
  EXPECT_EQ(u.cumulative(), (std::array<int64_t, 2>{1025, -1025}));
  // A reconnect without an unplug: the board either kept counting or restarted at 0.
  TickUnwrapper kept;
  kept.feed({20000, -20000});
  kept.rebase_either();
  EXPECT_EQ(kept.feed({20100, -20100}), (std::array<int64_t, 2>{100, -100}));
  kept.rebase_either();
  EXPECT_EQ(kept.feed({30, -30}), (std::array<int64_t, 2>{30, -30}));  // its watchdog cleared the counts
  // Many revolutions forward in 5000-count steps.
  for (int i = 1; i <= 100; ++i) {
    u.feed({static_cast<int16_t>(25 + 5000 * i), -25});
  }
  EXPECT_EQ(u.cumulative()[0], 1025 + 500000);
}

TEST(DiffDriveIntegrator, StraightForwardWithMirroredLeftMotor) {
  const Kinematics k = icart();
  DiffDriveIntegrator odo(k);
  // One wheel revolution: motor 0 +30000, motor 1 -30000 (mirrored) -> 2 pi R forward.
  odo.add({30000, -30000}, 1.0);
  EXPECT_NEAR(odo.pose().x, 2 * M_PI * 0.07455, 1e-12);
  EXPECT_NEAR(odo.pose().y, 0.0, 1e-12);
  EXPECT_NEAR(odo.pose().theta, 0.0, 1e-12);
  EXPECT_NEAR(odo.v(), 2 * M_PI * 0.07455, 1e-12);
  // Turning in place CCW: both motors count up (right forward, left backward).
  DiffDriveIntegrator spin(k);
  spin.add({1000, 1000}, 0.1);
  const double travel = 2 * M_PI * 0.07455 * 1000 / 30000;
  EXPECT_NEAR(spin.pose().theta, 2 * travel / 0.30737, 1e-12);
  EXPECT_NEAR(spin.pose().x, 0.0, 1e-12);
  EXPECT_NEAR(spin.omega(), 2 * travel / 0.30737 / 0.1, 1e-9);
}

TEST(DiffDriveIntegrator, ExactArcLandsOnTheCircleEulerDoesNot) {
  const Kinematics k = icart();
  // A quarter circle of radius rho driven in 40 coarse frames.
  const double rho = 1.0;
  const double quarter = M_PI / 2;
  const int frames = 40;
  const double right_travel = quarter * (rho + k.tread / 2) / frames;
  const double left_travel = quarter * (rho - k.tread / 2) / frames;
  // Choose ticks that are integers: scale the arc so the right wheel moves an exact count.
  const double per_tick = 2 * M_PI * 0.07455 / 30000;
  const auto r_ticks = static_cast<int64_t>(std::llround(right_travel / per_tick));
  const auto l_ticks = static_cast<int64_t>(std::llround(left_travel / per_tick));
  DiffDriveIntegrator exact(k, Integration::kExactArc);
  DiffDriveIntegrator euler(k, Integration::kEuler);
  for (int i = 0; i < frames; ++i) {
    exact.add({r_ticks, -l_ticks}, 0.005);
    euler.add({r_ticks, -l_ticks}, 0.005);
  }
  // The true arc from the (rounded) tick counts.
  const double ds = (r_ticks + l_ticks) * per_tick / 2;
  const double dth = (r_ticks - l_ticks) * per_tick / k.tread;
  const double theta = dth * frames;
  const double radius = ds / dth;
  const double x = radius * std::sin(theta);
  const double y = radius * (1 - std::cos(theta));
  EXPECT_NEAR(exact.pose().x, x, 1e-9);
  EXPECT_NEAR(exact.pose().y, y, 1e-9);
  EXPECT_NEAR(exact.pose().theta, theta, 1e-12);
  // Euler leads by half a step: its error is ~ ds * dtheta / 2 per step, mm over the quarter.
  const double euler_error = std::hypot(euler.pose().x - x, euler.pose().y - y);
  EXPECT_GT(euler_error, 0.01);
  EXPECT_NEAR(euler.pose().theta, theta, 1e-12);
}

TEST(FrameClock, BacklogCorrectionFilterAndLostFrames) {
  FrameClock clock(5000, 500);
  EXPECT_EQ(clock.stamp(1'000'000, 0).utime, 999'500);
  // Two frames arrive in one read 10 ms later: the first was one period earlier.
  const FrameStamp a = clock.stamp(1'010'000, 1);
  const FrameStamp b = clock.stamp(1'010'000, 0);
  EXPECT_EQ(a.utime, 1'004'500);
  EXPECT_EQ(b.utime, 1'009'500);
  EXPECT_EQ(a.lost + b.lost, 0);
  // Late arrival (USB jitter of 2 ms) moves the stamp only slightly off the 5 ms model.
  const FrameStamp late = clock.stamp(1'017'000, 0);
  EXPECT_GE(late.utime, 1'014'500);
  EXPECT_LT(late.utime, 1'014'600);
  // One read 6 ms late, then on time again: not a loss.
  const FrameStamp slow = clock.stamp(1'025'500, 0);
  EXPECT_EQ(slow.lost, 0);
  EXPECT_EQ(clock.stamp(1'025'000, 0).lost, 0);
  EXPECT_EQ(clock.stamp(1'030'000, 0).lost, 0);
  // A 20 ms gap (three frames missing): confirmed when the next frames stay late.
  int64_t lost = 0;
  int64_t t = 1'050'000;
  FrameStamp s;
  for (int i = 0; i < 6; ++i, t += 5000) {
    s = clock.stamp(t, 0);
    lost += s.lost;
  }
  EXPECT_EQ(lost, 3);
  EXPECT_EQ(clock.lost_total(), 3);
  EXPECT_NEAR(static_cast<double>(s.utime), static_cast<double>(t - 5000 - 500), 300.0);
}

}  // namespace
}  // namespace slamer::tfrog

// slamer-tfrog-sim --source-channel: wheel_encoders_t counts (left, right,
// forward-positive) become the board's motor counts (motor 0 right, motor 1
// left with the sign of its RADIUS), reached by whole-count ramps over each
// sample's interval, so the board's counts end exactly on the source's.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/wheels/ypspur_params.hpp"
#include "test/wheels/icart_mini_params.hpp"
#include "tools/tfrog_sim/tfrog_board.hpp"
#include "tools/tfrog_sim/wheel_path.hpp"

namespace slamer::tfrog {
namespace {

Kinematics icart_from_file() {
  return kinematics_from(RobotParams::from_file(icart_mini_param_file()));
}

TEST(EncoderFollower, MotorsEndOnTheSourceCountsWithTheRadiusSigns) {
  EncoderFollower follower(icart_from_file());
  TfrogBoard board;
  follower.add(1'000'000, 500, 700);  // the first sample is the reference
  follower.add(1'010'000, 500 + 123, 700 + 457);
  for (int tick = 0; tick < 10; ++tick) {
    const auto counts = follower.step();
    EXPECT_EQ(counts[0], std::round(counts[0]));  // whole counts per tick
    EXPECT_EQ(counts[1], std::round(counts[1]));
    EXPECT_GE(counts[0], 45.0);  // right wheel forward: 457 counts over 10 ticks
    EXPECT_LE(counts[0], 46.0);
    board.set_pushed(counts);
    board.step(1);
  }
  EXPECT_EQ(board.count(0), 457);   // motor 0 = right, RADIUS[0] > 0
  EXPECT_EQ(board.count(1), -123);  // motor 1 = left, mounted mirrored (RADIUS[1] < 0)
  const auto idle = follower.step();
  EXPECT_EQ(idle[0], 0.0);  // reached: nothing more until the next sample
  // A sample before the ramp ends restarts it from where the motors are; backwards too.
  follower.add(1'020'000, 500 + 100, 700 + 457 - 40);
  follower.add(1'025'000, 500 + 90, 700 + 457 - 60);
  board.set_pushed(follower.step());
  board.step(1);
  for (int tick = 0; tick < 20; ++tick) {
    board.set_pushed(follower.step());
    board.step(1);
  }
  EXPECT_EQ(board.count(0), 397);
  EXPECT_EQ(board.count(1), -90);
  EXPECT_EQ(follower.samples(), 4);
}

TEST(EncoderFollower, RampsLastTheSampleIntervalWithinOneToOneHundredTicks) {
  EncoderFollower follower(icart_from_file());
  follower.add(0, 0, 0);
  follower.add(500'000, 0, 1000);  // 0.5 s gap: ramp capped at 100 ticks
  double total = 0;
  int moving = 0;
  for (int tick = 0; tick < 200; ++tick) {
    const double c = follower.step()[0];
    total += c;
    moving += c != 0.0 ? 1 : 0;
  }
  EXPECT_EQ(total, 1000.0);
  EXPECT_EQ(moving, 100);
  follower.add(500'000, 0, 1003);  // same time: one tick
  EXPECT_EQ(follower.step()[0], 3.0);
  EXPECT_EQ(follower.step()[0], 0.0);
}

}  // namespace
}  // namespace slamer::tfrog

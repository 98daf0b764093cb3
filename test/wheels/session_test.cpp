// The driver session against the board model (tools/tfrog_sim/tfrog_board), byte for byte, in 1 ms steps.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/wheels/tfrog_session.hpp"
#include "test/wheels/icart_mini_params.hpp"
#include "tools/tfrog_sim/tfrog_board.hpp"

namespace slamer::tfrog {
namespace {

constexpr int64_t kStart = 1'700'000'000'000'000;

struct Rig {
  explicit Rig(SessionOptions options = {}, BoardOptions board_options = {})
      : session(options, RobotParams::from_file(icart_mini_param_file())), board(board_options) {
    session.opened(now);
  }
  // Runs `ms` milliseconds; `connected` false models a dead link (nothing delivered).
  void run(int ms, bool connected = true) {
    for (int i = 0; i < ms; ++i) {
      now += 1000;
      session.tick(now);
      const auto to_board = session.take_output();
      if (connected) {
        board.receive(to_board);
        board.step(1);
        const auto from_board = board.take_output();
        session.received(from_board, now);
      }
      for (const auto& s : session.take_samples()) {
        samples.push_back(s);
      }
    }
  }
  int64_t now = kStart;
  TfrogSession session;
  TfrogBoard board;
  std::vector<OdometrySample> samples;
};

TEST(TfrogSession, ConnectsLikeYpSpurAndStreamsInAFreeLevel) {
  Rig rig;
  rig.run(1500);
  const auto& status = rig.session.status();
  ASSERT_EQ(status.link, LinkState::kRunning) << status.last_problem;
  EXPECT_EQ(status.identity.vendor, "T-frog Project");
  EXPECT_EQ(status.identity.protocol, "YPP:11:02");
  EXPECT_FALSE(status.protocol_warning);
  EXPECT_EQ(rig.board.servo(0), 1);  // counter: free, but streaming
  EXPECT_EQ(rig.board.servo(1), 1);
  EXPECT_EQ(rig.board.watchdog_limit(), 300);
  EXPECT_EQ(rig.board.params().at({3, 0}), 650158);  // p_kv
  EXPECT_EQ(rig.board.params().at({100, 1}), 11);    // protocol_version
  EXPECT_GT(status.frames, 100);
  EXPECT_EQ(status.lost_frames, 0);
  EXPECT_FALSE(rig.samples.empty());
  // The watchdog is fed while free: run long past 300 ms.
  rig.run(3000);
  EXPECT_FALSE(rig.board.watchdog_expired());
  EXPECT_EQ(rig.board.servo(0), 1);
  EXPECT_FALSE(rig.session.should_close());
}

TEST(TfrogSession, PushedWheelsGiveOdometryAcrossTheInt16Wrap) {
  Rig rig;
  rig.run(1000);
  ASSERT_EQ(rig.session.status().link, LinkState::kRunning);
  const double x0 = rig.samples.back().pose.x;
  // Pushed forward at 100 counts/ms (0.156 m/s) for 10 s: 1e6 counts, 15 int16 wraps.
  rig.board.set_pushed({100.0, -100.0});
  rig.run(10000);
  rig.board.set_pushed({0.0, 0.0});
  rig.run(100);
  const double expected = 2 * M_PI * 0.07455 * 1e6 / 30000;
  EXPECT_NEAR(rig.samples.back().pose.x - x0, expected, 2 * M_PI * 0.07455 * 200 / 30000);
  EXPECT_NEAR(rig.samples.back().pose.theta, 0.0, 1e-9);
  EXPECT_NEAR(static_cast<double>(rig.samples.back().ticks[0]), 1e6, 200);
}

TEST(TfrogSession, VelocityCommandsWithinLimitsThenTimeoutStopsAtOnce) {
  Rig rig;
  rig.run(1000);
  ASSERT_EQ(rig.session.status().link, LinkState::kRunning);
  // 0.5 m/s straight: v = 0.5 -> wheel 6.707 rad/s -> 32.02 counts/ms -> 512 in 1/16.
  const auto values = rig.session.wheel_values(0.5, 0.0);
  EXPECT_EQ(values[0], 512);
  EXPECT_EQ(values[1], -512);
  rig.session.command(0.5, 0.0, rig.now);
  rig.run(20);
  EXPECT_EQ(rig.board.servo(0), 3);
  EXPECT_EQ(rig.board.servo(1), 3);
  // Acceleration limit: after ~20 ms at most 1.5 m/s^2 * 0.04 s.
  EXPECT_LE(std::abs(rig.board.w_ref16(0)), rig.session.wheel_values(0.06, 0.0)[0]);
  EXPECT_GT(rig.board.w_ref16(0), 0);
  for (int i = 0; i < 100; ++i) {  // commands at 100 Hz for 1 s
    rig.session.command(0.5, 0.0, rig.now);
    rig.run(10);
  }
  EXPECT_EQ(rig.board.w_ref16(0), 512);
  EXPECT_EQ(rig.board.w_ref16(1), -512);
  EXPECT_EQ(rig.session.status().drive, DriveState::kDriving);
  // Commands stop: velocity 0 within cmd_timeout (+1 ms), no ramp.
  const int64_t last = rig.now;
  int64_t zero_at = 0;
  for (int i = 0; i < 400 && zero_at == 0; ++i) {
    rig.run(1);
    if (rig.board.w_ref16(0) == 0 && rig.board.w_ref16(1) == 0) {
      zero_at = rig.now;
    } else {
      EXPECT_EQ(rig.board.w_ref16(0), 512);  // full speed until the stop: no ramp down
    }
  }
  ASSERT_GT(zero_at, 0);
  EXPECT_LE(zero_at - last, 202000);
  EXPECT_EQ(rig.session.status().drive, DriveState::kStopped);
  // Stays stopped without a new command.
  rig.run(2000);
  EXPECT_EQ(rig.board.w_ref16(0), 0);
  EXPECT_EQ(rig.board.servo(0), 3);
  EXPECT_FALSE(rig.board.watchdog_expired());
  // Limits: 5 m/s asks for MAX_VEL 0.9 at most.
  for (int i = 0; i < 200; ++i) {
    rig.session.command(5.0, 0.0, rig.now);
    rig.run(10);
  }
  EXPECT_EQ(rig.board.w_ref16(0), rig.session.wheel_values(0.9, 0.0)[0]);
  rig.session.command(NAN, 0.0, rig.now);
  EXPECT_EQ(rig.session.status().rejected_commands, 1);
  rig.session.stop_servos();
  rig.run(1);
  EXPECT_EQ(rig.board.servo(0), 0);
  EXPECT_EQ(rig.board.servo(1), 0);
}

TEST(TfrogSession, TimeoutByServoStopWhenConfigured) {
  SessionOptions options;
  options.timeout_servo_stop = true;
  Rig rig(options);
  rig.run(1000);
  rig.session.command(0.3, 0.5, rig.now);
  rig.run(100);
  EXPECT_EQ(rig.board.servo(0), 3);
  rig.run(150);
  EXPECT_EQ(rig.board.servo(0), 0);
  EXPECT_EQ(rig.board.servo(1), 0);
  rig.run(1000);  // later back to the free level, streaming, not driving
  EXPECT_EQ(rig.board.servo(0), 1);
  EXPECT_FALSE(rig.session.should_close());
}

TEST(TfrogSession, ReadsEmbeddedParametersWhenConfigured) {
  SessionOptions options;
  options.use_embedded_param = true;
  BoardOptions board;
  // The board's copy says the wheels are 10 % larger.
  std::string text =
      "COUNT_REV 400\nVOLT 24\nCYCLE 0.001\nGEAR 75\nMOTOR_R 0.75\nTORQUE_FINENESS 0.000001\n"
      "RADIUS[0] 0.082\nRADIUS[1] -0.082\nTREAD 0.30737\nTORQUE_MAX 0.05\nTORQUE_LIMIT 0.4\n"
      "MAX_VEL 0.9\nMAX_W 3.14\nMAX_ACC_V 1.5\nMAX_ACC_W 6.28\nINTEGRAL_MAX 0.05\nMOTOR_VC 630.0\n"
      "MOTOR_TC 0.01515\nGAIN_KP 80\nGAIN_KI 250\n";
  board.embedded_param = text;
  Rig rig(options, board);
  rig.run(2000);
  ASSERT_EQ(rig.session.status().link, LinkState::kRunning) << rig.session.status().last_problem;
  EXPECT_DOUBLE_EQ(rig.session.kinematics().radius[0], 0.082);
  EXPECT_EQ(rig.board.servo(0), 1);
}

TEST(TfrogSession, RejectsAnIncompatibleBoardAfterThreeTries) {
  BoardOptions old_board;
  old_board.protocol = "YPP:05:00";
  Rig rig({}, old_board);
  rig.run(3000);
  EXPECT_TRUE(rig.session.should_close());
  EXPECT_NE(rig.session.close_reason().find("YPP:05:00"), std::string::npos) << rig.session.close_reason();
  EXPECT_EQ(rig.board.text_commands(), 4);  // the banner's VV, then 3 tries
  EXPECT_EQ(rig.board.servo(0), 0);
}

TEST(TfrogSession, SilenceClosesAndAReplugContinuesWithoutAJump) {
  Rig rig;
  rig.run(1000);
  rig.board.set_pushed({10.0, -10.0});
  rig.run(1000);
  rig.board.set_pushed({0.0, 0.0});
  rig.run(50);
  const auto before = rig.samples.back();
  rig.run(400, false);  // unplugged
  ASSERT_TRUE(rig.session.should_close());
  rig.session.closed(rig.session.close_reason());
  EXPECT_EQ(rig.session.status().link, LinkState::kClosed);
  // Re-plugged: a fresh board with counters at 0.
  rig.board = TfrogBoard();
  rig.session.opened(rig.now);
  rig.run(1500);
  ASSERT_EQ(rig.session.status().link, LinkState::kRunning);
  EXPECT_EQ(rig.session.status().reconnects, 1);
  const auto after = rig.samples.back();
  EXPECT_EQ(after.ticks, before.ticks);
  EXPECT_NEAR(after.pose.x, before.pose.x, 1e-12);
  // And counting continues from there.
  rig.board.set_pushed({10.0, -10.0});
  rig.run(100);
  EXPECT_NEAR(static_cast<double>(rig.samples.back().ticks[0] - before.ticks[0]), 1000.0, 60.0);
}

TEST(TfrogSession, CountsDamagedAndWrongLengthFramesAndErrorStates) {
  Rig rig;
  rig.board.knobs().corrupt_every = 10;
  rig.board.knobs().wrong_length_every = 25;
  rig.board.knobs().error_bits = {kErrorLowVoltage, 0};
  rig.run(1000);
  rig.session.command(0.1, 0.0, rig.now);  // VELOCITY: the board reports error states
  for (int i = 0; i < 50; ++i) {
    rig.session.command(0.1, 0.0, rig.now);
    rig.run(20);
  }
  const auto& status = rig.session.status();
  EXPECT_GT(status.bad_frames, 10);
  EXPECT_GT(status.wrong_length, 3);
  EXPECT_EQ(status.error_bits[0], kErrorLowVoltage);
  EXPECT_EQ(status.error_bits[1], 0);
  EXPECT_FALSE(rig.session.should_close());
}

}  // namespace
}  // namespace slamer::tfrog

// The pieces the localizer's status and robustness rest on, each alone: the
// process state's reason, the odometry agreement window, the status options'
// key errors, the scan fit and the motion noise of a zero increment. The
// filter in the loop with them is robustness_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "localizer/localizer_messages.hpp"
#include "localizer/motion_model.hpp"
#include "localizer/odometry_agreement.hpp"
#include "localizer/particle_filter.hpp"
#include "localizer/scan_fit.hpp"
#include "slamer/process_status_t.hpp"
#include "test/localizer/options_error.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

// PROCESS_STATUS says why the pose is not OK, in the filter's words.
TEST(ProcessState, SaysWhyThePoseIsUncertainOrLost) {
  const InputHealth health;
  const LocalizerChannels channels;
  const auto uncertain = process_state(LocalizerStatus::kUncertain, "the particles are spread", health, channels);
  EXPECT_EQ(uncertain.first, process_status_t::DEGRADED);
  EXPECT_EQ(uncertain.second, "uncertain: the particles are spread");
  const auto lost = process_state(LocalizerStatus::kLost, "the scans do not fit the map", health, channels);
  EXPECT_EQ(lost.first, process_status_t::ERROR);
  EXPECT_EQ(lost.second, "lost: the scans do not fit the map");
  const auto ok = process_state(LocalizerStatus::kOk, "", health, channels);
  EXPECT_EQ(ok.first, process_status_t::OK);
  EXPECT_EQ(ok.second, "");
}

TEST(OdometryAgreement, TheEstimatesTravelAlongItsHeadingAgainstTheOdometrysOverTheWindow) {
  OdometryAgreement agreement(2.0, 100.0);
  const double heading = 0.7;
  Pose2 pose{1.0, 2.0, heading};
  const auto move = [&](double forward, double sideways) {
    return Pose2{pose.x + forward * std::cos(heading) - sideways * std::sin(heading),
                 pose.y + forward * std::sin(heading) + sideways * std::cos(heading), heading};
  };
  int64_t utime = 0;
  // 1 s agreeing at 0.6 m/s, and moving sideways (heading drift's part) does not count.
  for (int k = 0; k < 10; ++k, utime += 100'000) {
    const Pose2 next = move(0.06, 0.02);
    agreement.add(utime, pose, next, 0.06);
    pose = next;
  }
  EXPECT_NEAR(agreement.along_track(), 0.0, 1e-12);
  // 1 s where the estimate goes half as far as the wheels: -0.3 m.
  for (int k = 0; k < 10; ++k, utime += 100'000) {
    const Pose2 next = move(0.03, 0.0);
    agreement.add(utime, pose, next, 0.06);
    pose = next;
  }
  EXPECT_NEAR(agreement.along_track(), -0.3, 1e-9);
  // Backwards both: agreeing.
  agreement.add(utime, pose, move(-0.05, 0.0), -0.05);
  EXPECT_NEAR(agreement.along_track(), -0.3, 1e-9);
  // 2 s later the slow second has left the window.
  for (int k = 0; k < 20; ++k, utime += 100'000) {
    agreement.add(utime, pose, move(0.06, 0.0), 0.06);
  }
  EXPECT_NEAR(agreement.along_track(), 0.0, 1e-9);
  // Time going back starts over; NaN is ignored; a window of 0 is off.
  agreement.add(utime, pose, move(0.5, 0.0), 0.0);
  EXPECT_NEAR(agreement.along_track(), 0.5, 1e-9);
  agreement.add(utime - 5'000'000, pose, move(0.1, 0.0), 0.0);
  EXPECT_NEAR(agreement.along_track(), 0.1, 1e-9);
  agreement.add(utime, pose, move(0.1, 0.0), std::nan(""));
  EXPECT_NEAR(agreement.along_track(), 0.1, 1e-9);
  OdometryAgreement off(0.0, 5.0);
  off.add(0, pose, move(1.0, 0.0), 0.0);
  EXPECT_EQ(off.along_track(), 0.0);
}

// The window ends where the odometry has driven `distance`: 1 m steps (a
// sparse log) each 5 % short add up over 10 s to 0.5 m, over the last 3 m to 0.15 m.
TEST(OdometryAgreement, TheWindowEndsWhereTheOdometryHasDrivenTheDistance) {
  OdometryAgreement agreement(10.0, 3.0);
  Pose2 pose;
  for (int k = 0; k < 10; ++k) {
    const Pose2 next{pose.x + 0.95, 0.0, 0.0};
    agreement.add(100'000LL * k, pose, next, 1.0);
    pose = next;
  }
  EXPECT_NEAR(agreement.along_track(), -0.15, 1e-9);
  OdometryAgreement by_time(10.0, 100.0);
  pose = {};
  for (int k = 0; k < 10; ++k) {
    const Pose2 next{pose.x + 0.95, 0.0, 0.0};
    by_time.add(100'000LL * k, pose, next, 1.0);
    pose = next;
  }
  EXPECT_NEAR(by_time.along_track(), -0.5, 1e-9);
}

TEST(StatusOptions, FitThresholdsOutOfOrderAreRefusedWithTheirKey) {
  const auto error_of = localizer_options_error;
  EXPECT_EQ(error_of("status: {fit_confirm: 0.75, fit_sustained: 0.65}\n"), "");
  EXPECT_NE(error_of("status: {fit_confirm: 0.95}\n").find("'status.fit_confirm'"), std::string::npos)
      << error_of("status: {fit_confirm: 0.95}\n");
  EXPECT_NE(error_of("status: {fit_sustained: 0.4}\n").find("'status.fit_sustained'"), std::string::npos)
      << error_of("status: {fit_sustained: 0.4}\n");
  EXPECT_NE(error_of("status: {fit_sustained_time: 0}\n").find("'status.fit_sustained_time'"), std::string::npos);
  EXPECT_NE(error_of("status: {odometry_disagreement: -0.1}\n").find("'status.odometry_disagreement'"),
            std::string::npos);
  EXPECT_NE(error_of("status: {odometry_disagreement_time: 0}\n").find("'status.odometry_disagreement_time'"),
            std::string::npos);
  EXPECT_NE(error_of("status: {odometry_disagreement_distance: 0}\n").find("'status.odometry_disagreement_distance'"),
            std::string::npos);
  EXPECT_EQ(error_of("status: {along_track_gain: 0, along_track_time: 0}\n"), "");
  EXPECT_NE(error_of("status: {along_track_gain: -0.1}\n").find("'status.along_track_gain'"), std::string::npos);
  EXPECT_NE(error_of("status: {along_track_time: 601}\n").find("'status.along_track_time'"), std::string::npos);
  EXPECT_NE(error_of("status: {along_track_scans: 0}\n").find("'status.along_track_scans'"), std::string::npos);
  EXPECT_NE(error_of("status: {along_track_pin: maybe}\n").find("'status.along_track_pin'"), std::string::npos);
}

TEST(ScanFit, FractionOfBeamsOnTheMapsObstacles) {
  const SmallWorld w;
  const DistanceField obstacles = obstacle_distance_field(w.map, 1.0);
  const Pose2 truth{2.0, 3.0, 0.0};
  const LaserScan scan = w.scan_at(truth);
  const ScanPoints points = end_points(scan, w.map.geometry.resolution);
  const auto fit = [&](const Pose2& pose) {
    return scan_fit(obstacles, points, sensor_in_cells(w.map.geometry, pose, w.robot.lidar.mount), 0.1);
  };
  EXPECT_GT(fit(truth), 0.85);  // the box the map does not have takes some beams
  EXPECT_LT(fit({2.3, 3.0, 0.0}), 0.6);
  EXPECT_LT(fit({2.0, 3.0, 0.1}), 0.6);
  EXPECT_LT(fit({8.5, 1.2, 2.5}), 0.3);
  EXPECT_EQ(scan_fit(obstacles, {}, {}, 0.1), 0.0);
}

// The floor per scan is for scans noise_floor_interval (0.25 s) or more
// apart; closer ones each get sqrt(dt / 0.25 s) of it, so that a 40 Hz
// scanner does not spread the particles sqrt(10) times as fast as a 4 Hz one.
TEST(MotionModel, ZeroIncrementSpreadsOnlyWhenTheGainIsUpAndWithTheTimeBetweenScans) {
  LocalizerOptions o;
  std::mt19937 rng(2);
  const OdometryIncrement zero{};
  double spread_rest = 0.0;
  double heading_slow = 0.0;
  double heading_fast = 0.0;
  double position_slow = 0.0;
  for (int i = 0; i < 2000; ++i) {
    spread_rest = std::max(spread_rest, std::abs(sample_motion({}, zero, o.motion, rng, 1.0, 2.0).theta));
    const Pose2 slow = sample_motion({}, zero, o.motion, rng, 4.0, 2.0);
    heading_slow += slow.theta * slow.theta;
    position_slow += slow.x * slow.x + slow.y * slow.y;
    heading_fast += std::pow(sample_motion({}, zero, o.motion, rng, 4.0, 0.025).theta, 2);
  }
  EXPECT_EQ(spread_rest, 0.0);  // a filter that explains its scans keeps the configured noise
  const double rot = 3.0 * o.motion.noise_floor_rot;
  EXPECT_NEAR(std::sqrt(heading_slow / 2000), rot, 0.1 * rot);
  EXPECT_NEAR(std::sqrt(heading_fast / 2000), rot * std::sqrt(0.1), 0.1 * rot * std::sqrt(0.1));
  const double trans = 3.0 * o.motion.noise_floor_trans;
  EXPECT_NEAR(std::sqrt(position_slow / 2000), trans, 0.1 * trans);
  const Pose2 backwards = sample_motion({1.0, 2.0, 0.5}, zero, o.motion, rng, 4.0, -1.0);  // time went backwards
  EXPECT_EQ(backwards.x, 1.0);
  EXPECT_EQ(backwards.y, 2.0);
  EXPECT_EQ(backwards.theta, 0.5);
}

// Through the filter: a scan that fits nowhere near the estimate raises the
// gain to its largest, and a zero increment then spreads the cloud's heading
// by the floor's share of the time the increment took, 0.025 s or 0.25 s.
TEST(MotionModel, TheFiltersPredictionSpreadsAZeroIncrementByTheFloorOfItsTime) {
  const SmallWorld w;
  LocalizerOptions o;
  o.mode = LocalizerMode::kLfm;
  o.particles = 4000;
  o.lfm.beam_step = 4;
  const auto heading_variance = [](const std::vector<Particle>& particles) {
    double sum = 0.0;
    double squares = 0.0;
    for (const Particle& p : particles) {
      sum += p.pose.theta;
      squares += p.pose.theta * p.pose.theta;
    }
    const double n = static_cast<double>(particles.size());
    return squares / n - (sum / n) * (sum / n);
  };
  for (const double seconds : {0.025, 0.25}) {
    ParticleFilter filter(w.map, o, w.robot.lidar.mount);
    filter.initialize({2.0, 3.0, 0.0}, {0.001, 0.001, 0.0001});
    LaserScan elsewhere = w.scan_at({8.5, 1.2, 2.5});
    elsewhere.utime = 1'000'000;
    const UpdateResult r = filter.update(elsewhere, nullptr);
    ASSERT_LT(r.fit, o.status.fit_lost);
    ASSERT_DOUBLE_EQ(r.noise_gain, o.motion.noise_gain_max);
    const double before = heading_variance(filter.particles());
    filter.predict({}, {}, seconds);
    const double added = std::sqrt(heading_variance(filter.particles()) - before);
    const double expected = (o.motion.noise_gain_max - 1.0) * o.motion.noise_floor_rot *
                            std::sqrt(std::min(seconds / o.motion.noise_floor_interval, 1.0));
    EXPECT_NEAR(added, expected, 0.05 * expected) << seconds << " s";
  }
}

// The motion model's heavy tail: while the base moves, heading_slip_fraction
// of the draws turn by an extra N(0, heading_slip_sigma), a slip 50 times the
// alphas' spread; the rest keep the alphas' noise, and a base that stands does not slip.
TEST(MotionModel, AFractionOfTheDrawsOfAMovingBaseSlipInHeading) {
  LocalizerOptions o;
  o.motion.heading_slip_fraction = 0.05;
  o.motion.heading_slip_sigma = 0.02;
  std::mt19937 rng(5);
  const OdometryIncrement step = decompose({}, {0.02, 0.0, 0.0});  // one scan at 0.8 m/s and 40 Hz
  const double alphas_sd = o.motion.alpha_rot_from_trans * 0.02;   // 0.0004 rad for each of rot1 and rot2
  const int n = 40000;
  int slipped = 0;
  double slip_squares = 0.0;
  for (int i = 0; i < n; ++i) {
    const double turn = sample_motion({}, step, o.motion, rng).theta;
    if (std::abs(turn) > 10.0 * alphas_sd) {  // the alphas alone: 7 standard deviations of rot1 + rot2
      ++slipped;
      slip_squares += turn * turn;
    }
  }
  // 5 % slip, of them 84 % more than 0.004 rad (|N(0, 0.02)| > 0.2 sigma).
  EXPECT_NEAR(static_cast<double>(slipped) / n, 0.05 * 0.84, 0.004);
  // Their spread: N(0, 0.02) beyond 0.2 sigma has an RMS of 1.089 sigma.
  EXPECT_NEAR(std::sqrt(slip_squares / slipped), 1.089 * 0.02, 0.0015);
  const OdometryIncrement standing{};
  double largest = 0.0;
  for (int i = 0; i < 2000; ++i) {
    largest = std::max(largest, std::abs(sample_motion({}, standing, o.motion, rng).theta));
  }
  EXPECT_EQ(largest, 0.0);
  o.motion.heading_slip_fraction = 0.0;
  int beyond = 0;
  for (int i = 0; i < n; ++i) {
    beyond += std::abs(sample_motion({}, step, o.motion, rng).theta) > 10.0 * alphas_sd;
  }
  EXPECT_EQ(beyond, 0);
}

TEST(MotionOptions, AHeadingSlipOutOfRangeIsRefusedWithItsKey) {
  const auto error_of = localizer_options_error;
  EXPECT_EQ(error_of("motion: {heading_slip_fraction: 0, heading_slip_sigma: 0}\n"), "");
  for (const char* bad : {"-0.1", "1.5", "nan", "many"}) {
    EXPECT_NE(
        error_of(std::string("motion: {heading_slip_fraction: ") + bad + "}\n").find("'motion.heading_slip_fraction'"),
        std::string::npos)
        << bad;
    EXPECT_NE(error_of(std::string("motion: {heading_slip_sigma: ") + bad + "}\n").find("'motion.heading_slip_sigma'"),
              std::string::npos)
        << bad;
  }
}

// The floor's interval divides the time between scans: zero, negative or not
// a number is refused with its key.
TEST(MotionOptions, AFloorIntervalThatIsNotAPositiveTimeIsRefusedWithItsKey) {
  const auto error_of = localizer_options_error;
  EXPECT_EQ(error_of("motion: {noise_floor_interval: 0.1}\n"), "");
  for (const char* bad : {"0", "-0.25", "nan", "inf", "soon"}) {
    EXPECT_NE(
        error_of(std::string("motion: {noise_floor_interval: ") + bad + "}\n").find("'motion.noise_floor_interval'"),
        std::string::npos)
        << bad;
  }
}

}  // namespace
}  // namespace slamer

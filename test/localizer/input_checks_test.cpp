// The plausibility rules of the localizer's inputs (input_checks.hpp): each
// bad message of the fault probing is refused with its reason.
#include "localizer/input_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace slamer {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

LaserScan good_scan() {
  LaserScan scan;
  scan.utime = kT0;
  scan.angle_min = -2.0;
  scan.angle_increment = 0.004;
  scan.range_min = 0.1f;
  scan.range_max = 30.0f;
  scan.ranges.assign(1000, 3.0f);
  return scan;
}

TEST(InputChecks, ScansWithImpossibleGeometryAreRefused) {
  const InputLimits limits;
  EXPECT_EQ(scan_problem(good_scan(), limits), "");
  LaserScan scan = good_scan();
  scan.angle_increment = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(scan_problem(scan, limits).find("impossible angles"), std::string::npos);
  scan = good_scan();
  scan.range_max = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(scan_problem(scan, limits), "impossible range limits");
  for (const std::size_t beams : {0u, 1u, 2u, 1082u}) {
    scan = good_scan();
    scan.angle_increment = 0.001;
    scan.ranges.assign(beams, 3.0f);
    EXPECT_EQ(scan_problem(scan, limits), std::to_string(beams) + " beams (the sensor has 1081)");
  }
  scan = good_scan();
  scan.utime = 0;
  EXPECT_EQ(scan_problem(scan, limits), "utime 0 is no time");
  // Not one measured range (all NaN, +inf or 1e30): nothing to use, and refused before it can
  // make the real scan in flight stale (fault probing: 12 real scans lost that way).
  for (const float r : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 1e30f}) {
    scan = good_scan();
    scan.ranges.assign(1000, r);
    EXPECT_EQ(scan_problem(scan, limits), "no range within [range_min, range_max] in 1000 beams") << r;
  }
  scan.ranges[500] = 12.0f;  // one is enough
  EXPECT_EQ(scan_problem(scan, limits), "");
}

TEST(InputChecks, OneMessageFarInTimeIsRefusedButAStreamThatMovedIsFollowed) {
  StreamTime time{InputLimits{}};
  EXPECT_EQ(time.check(kT0), TimeVerdict::kAccept);
  EXPECT_EQ(time.check(kT0 + 25'000), TimeVerdict::kAccept);
  EXPECT_EQ(time.check(kT0 + 3'600'000'000), TimeVerdict::kRefuse);  // an hour ahead, once
  EXPECT_EQ(time.check(kT0 + 50'000), TimeVerdict::kAccept);         // the stream goes on
  EXPECT_EQ(time.check(1), TimeVerdict::kRefuse);                    // utime ~0, once
  EXPECT_EQ(time.check(kT0 + 75'000), TimeVerdict::kAccept);
  // The log played again from its start: three scans agree, the stream has moved.
  EXPECT_EQ(time.check(kT0 - 60'000'000), TimeVerdict::kRefuse);
  EXPECT_EQ(time.check(kT0 - 59'975'000), TimeVerdict::kRefuse);
  EXPECT_EQ(time.check(kT0 - 59'950'000), TimeVerdict::kMoved);
  EXPECT_EQ(time.check(kT0 - 59'925'000), TimeVerdict::kAccept);
}

TEST(InputChecks, ASparseStreamMayStepAsFarAsItsPaceSays) {
  StreamTime time{InputLimits{}};
  // A log with a scan every 3 s (aces): 2 s is no bound for it.
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(time.check(kT0 + 3'000'000LL * k), TimeVerdict::kAccept) << k;
  }
  EXPECT_EQ(time.check(kT0 + 3'000'000LL * 19 + 3'600'000'000LL), TimeVerdict::kRefuse);  // an hour is still far
}

TEST(InputChecks, OdometryFasterThanTheRobotIsAJump) {
  const InputLimits limits;  // 0.9 m/s, 3.14 rad/s, 5 cm / 0.05 rad margin
  EXPECT_EQ(odometry_step_problem({0, 0, 0}, kT0, {0.01, 0, 0.02}, kT0 + 10'000, limits), "");
  EXPECT_EQ(odometry_step_problem({0, 0, 0}, kT0, {1.7, 0, 0}, kT0 + 10'000, limits),
            "a jump of 1.70 m and 0.00 rad in 0.010 s");
  EXPECT_NE(odometry_step_problem({0, 0, 0}, kT0, {0, 0, 2.0}, kT0 + 10'000, limits), "");
  EXPECT_EQ(odometry_step_problem({0, 0, 0}, kT0, {0.5, 0, 0}, kT0 + 1'000'000, limits), "");  // 1 s gap, 0.5 m
  EXPECT_EQ(odometry_step_problem({0, 0, 0}, kT0, {std::nan(""), 0, 0}, kT0 + 10'000, limits), "not a finite pose");
}

TEST(InputChecks, ASeqGoingBackWhileTimeGoesOnIsADriversRestart) {
  StreamRestart stream;
  EXPECT_EQ(stream.check(7, 1'000'000), "");
  EXPECT_EQ(stream.check(8, 1'025'000), "");
  EXPECT_EQ(stream.check(7, 1'000'000), "");   // a late one (out of order): back in both
  EXPECT_EQ(stream.check(20, 1'350'000), "");  // messages lost: a gap, not a restart
  EXPECT_EQ(stream.check(0, 1'500'000), "seq 20 -> 0 after 0.15 s");
  EXPECT_EQ(stream.check(1, 1'525'000), "");
}

TEST(InputChecks, InitialPoseNeedsAFinitePoseOnTheMapAndAProperCovariance) {
  const std::array<double, 9> good{0.04, 0, 0, 0, 0.04, 0, 0, 0, 0.01};
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, good, true), "");
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, good, false), "a position (1.00, 2.00) off the map");
  EXPECT_EQ(initial_pose_problem({std::nan(""), 2, 0}, good, true), "not a finite pose");
  std::array<double, 9> negative = good;
  negative[4] = -0.01;
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, negative, true), "a covariance that is not positive semi-definite");
  std::array<double, 9> indefinite{1, 2, 0, 2, 1, 0, 0, 0, 1};  // eigenvalues 3, -1, 1
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, indefinite, true), "a covariance that is not positive semi-definite");
  std::array<double, 9> skew = good;
  skew[1] = 0.01;
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, skew, true), "a covariance that is not symmetric");
  std::array<double, 9> huge = good;
  huge[0] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(initial_pose_problem({1, 2, 0}, huge, true), "a covariance that is not finite");
}

TEST(InputChecks, RefusalsAreCountedPerChannelAndSummarizedOnce) {
  RefusalCounter counter;
  counter.count("LIDAR", "2 beams");
  counter.count("LIDAR", "0 beams");
  counter.count("ODOMETRY", "a jump");
  EXPECT_EQ(counter.total("LIDAR"), 2);
  EXPECT_EQ(counter.total("POSE"), 0);
  EXPECT_EQ(counter.take_summary(), "refused LIDAR 2 (last: 0 beams), ODOMETRY 1 (last: a jump)");
  EXPECT_EQ(counter.take_summary(), "");
  EXPECT_EQ(counter.total("LIDAR"), 2);
}

}  // namespace
}  // namespace slamer

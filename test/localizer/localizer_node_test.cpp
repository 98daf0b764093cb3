// LocalizerNode: pairing scans with objects, stale and backwards input,
// missing streams; the filter's status; the saved pose file and its atomic write.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/process/atomic_file.hpp"
#include "localizer/localizer_node.hpp"
#include "localizer/saved_pose.hpp"
#include "test/localizer/options_error.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

constexpr int64_t kFlush = std::numeric_limits<int64_t>::max();

LocalizerOptions node_options(LocalizerMode mode) {
  LocalizerOptions options;
  options.mode = mode;
  options.particles = 100;
  options.initial_pose = {2.0, 3.0, 0.0};
  options.initial_sigma = {0.01, 0.01, 0.01};
  return options;
}

LineObjectSet objects_for(int64_t utime) {
  LineObjectSet set;
  set.utime = utime;
  set.class_names = {"others"};
  return set;
}

TEST(LocalizerNode, OdometryBetweenScansMovesTheEstimate) {
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kLfm), w.robot.lidar.mount);
  // Odometry in its own frame (starting at 0), 100 Hz, driving +x at 0.5 m/s; scans at 40 Hz.
  std::optional<UpdateResult> last;
  for (int step = 0; step <= 200; ++step) {
    const int64_t t = 10'000 * step;
    node.on_odometry(t, {0.005 * step, 0.0, 0.0});
    if (step % 4 == 0 && step > 0) {  // a scan at t - 15 ms, delivered now
      LaserScan scan = w.scan_at({2.0 + 0.005 * step - 0.0075, 3.0, 0.0});
      scan.utime = t - 15'000;
      node.on_scan(scan);
      while (auto out = node.poll(t)) {
        last = out;
      }
    }
  }
  ASSERT_TRUE(last.has_value());
  EXPECT_NEAR(last->estimate.pose.x, 2.0 + 1.0 - 0.0075, 0.05);
  EXPECT_NEAR(last->estimate.pose.y, 3.0, 0.05);
  EXPECT_EQ(node.counters().scans_without_odometry, 0);
  EXPECT_FALSE(node.health().odometry_missing);
  // LFM does not wait for objects, so the recognizer's output is not "stale" input to it.
  node.on_objects(objects_for(last->semantic.utime));
  EXPECT_EQ(node.counters().stale_objects, 0);
  EXPECT_EQ(node.counters().scans_without_objects, 0);
  EXPECT_FALSE(node.health().objects_missing);
}

// Odometry is interpolated to a scan's time. A scan read before the odometry
// past its time (a stalled host delivers both in a burst; the recognizer's
// replayed objects come right after their scan) waits for it, so the result
// does not depend on which came first; up to odometry_wait if it does not come.
TEST(LocalizerNode, AScanReadBeforeTheOdometryPastItsTimeWaitsForIt) {
  const SmallWorld w;
  const auto odometry_at = [](int64_t t) { return Pose2{0.5e-6 * static_cast<double>(t), 0.0, 0.0}; };  // 0.5 m/s
  const auto feed_until = [&](LocalizerNode& node, int64_t until) {
    for (int64_t t = 10'000; t <= until; t += 10'000) {
      node.on_odometry(t, odometry_at(t));
    }
  };
  LaserScan first = w.scan_at({2.0, 3.0, 0.0});
  first.utime = 0;
  LaserScan scan = w.scan_at({2.0 + 0.5 * 0.105, 3.0, 0.0});
  scan.utime = 105'000;
  std::vector<Pose2> estimates;
  for (const bool scan_first : {false, true}) {
    LocalizerNode node(w.map, node_options(LocalizerMode::kLfm), w.robot.lidar.mount);
    node.on_odometry(0, odometry_at(0));
    node.on_scan(first, 10'000);
    ASSERT_TRUE(node.poll(10'000).has_value());
    feed_until(node, 100'000);
    if (scan_first) {
      node.on_scan(scan, 120'000);
      EXPECT_FALSE(node.poll(120'000).has_value());  // odometry up to 100 ms only
      EXPECT_FALSE(node.poll(169'999).has_value());
    }
    node.on_odometry(110'000, odometry_at(110'000));
    if (!scan_first) {
      node.on_scan(scan, 120'000);
    }
    const std::optional<UpdateResult> result = node.poll(120'000);
    ASSERT_TRUE(result.has_value());
    estimates.push_back(result->estimate.pose);
  }
  EXPECT_EQ(estimates[0].x, estimates[1].x);
  EXPECT_EQ(estimates[0].y, estimates[1].y);
  EXPECT_EQ(estimates[0].theta, estimates[1].theta);
  EXPECT_NEAR(estimates[0].x, 2.0 + 0.5 * 0.105, 0.03);
  // Odometry that does not come: the scan goes after odometry_wait (50 ms) with the latest.
  LocalizerNode node(w.map, node_options(LocalizerMode::kLfm), w.robot.lidar.mount);
  node.on_odometry(0, odometry_at(0));
  node.on_scan(first, 10'000);
  ASSERT_TRUE(node.poll(10'000).has_value());
  feed_until(node, 100'000);
  node.on_scan(scan, 120'000);
  EXPECT_FALSE(node.poll(169'999).has_value());
  EXPECT_TRUE(node.poll(170'000).has_value());
  EXPECT_FALSE(node.health().odometry_missing);
}

TEST(LocalizerOptions, OdometryWaitIsANonNegativeSpanInSeconds) {
  EXPECT_EQ(localizer_options_error("inputs: {odometry_wait: 0}\n"), "");
  for (const char* bad : {"-0.01", "11", "nan", "soon"}) {
    const std::string error = localizer_options_error(std::string("inputs: {odometry_wait: ") + bad + "}\n");
    EXPECT_NE(error.find("'inputs.odometry_wait'"), std::string::npos) << bad << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(LocalizerNode, ScansWaitInOrderForTheirObjects) {
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kSlamer), w.robot.lidar.mount);
  node.on_odometry(0, {});
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  for (const int64_t t : {1'000'000, 1'025'000, 1'050'000}) {
    scan.utime = t;
    node.on_scan(scan);
  }
  EXPECT_FALSE(node.poll(1'060'000).has_value());  // the first waited 60 ms of 100
  // The second scan's objects: the first scan's will not come any more.
  node.on_objects(objects_for(1'025'000));
  std::optional<UpdateResult> first = node.poll(1'060'000);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->semantic.utime, 1'000'000);
  std::optional<UpdateResult> second = node.poll(1'060'000);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->semantic.utime, 1'025'000);
  EXPECT_FALSE(node.poll(1'060'000).has_value());  // the third waits
  EXPECT_EQ(node.counters().scans_without_objects, 1);
  // Late objects of the first scan, and a duplicate of the second's: dropped and counted.
  node.on_objects(objects_for(1'000'000));
  node.on_objects(objects_for(1'025'000));
  EXPECT_EQ(node.counters().stale_objects, 2);
  EXPECT_EQ(node.counters().objects_without_scan, 0);
  // Objects of a scan that never came here (UDP lost it on the way to us
  // alone): not late, counted apart, and the third scan still waits.
  node.on_objects(objects_for(1'037'500));
  EXPECT_EQ(node.counters().objects_without_scan, 1);
  EXPECT_EQ(node.counters().stale_objects, 2);
  // The third scan goes without objects once objects_wait has passed.
  EXPECT_FALSE(node.poll(1'149'000).has_value());
  ASSERT_TRUE(node.poll(1'150'000).has_value());
  EXPECT_EQ(node.counters().scans_without_objects, 2);
  EXPECT_FALSE(node.health().objects_missing);  // objects came 125 ms before
}

TEST(LocalizerNode, ObjectsThatComeBeforeTheirScanWaitForIt) {
  // The driver and the recognizer send from two sockets: nothing orders their
  // datagrams at this receiver, so a scan's objects may come first.
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kSlamer), w.robot.lidar.mount);
  node.on_odometry(0, {});
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  scan.utime = 1'000'000;
  node.on_scan(scan);
  node.on_objects(objects_for(1'000'000));
  ASSERT_TRUE(node.poll(1'000'000).has_value());
  // The next two scans' objects before the scans; the second's twice.
  node.on_objects(objects_for(1'025'000));
  node.on_objects(objects_for(1'050'000));
  node.on_objects(objects_for(1'050'000));
  EXPECT_EQ(node.counters().objects_without_scan, 0);
  EXPECT_EQ(node.counters().stale_objects, 1);
  scan.utime = 1'025'000;
  node.on_scan(scan);
  std::optional<UpdateResult> second = node.poll(1'025'000);  // with its objects, at once
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->semantic.utime, 1'025'000);
  // Held objects of a scan that never comes: a later scan shows it will not.
  node.on_objects(objects_for(1'100'000));
  scan.utime = 1'075'000;  // 1'050'000 was lost on the way here
  node.on_scan(scan);
  EXPECT_EQ(node.counters().objects_without_scan, 1);
  // The waiting scan goes without objects now: the held ones are of a later scan.
  std::optional<UpdateResult> third = node.poll(1'075'000);
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(node.counters().scans_without_objects, 1);
  scan.utime = 1'100'000;
  node.on_scan(scan);
  ASSERT_TRUE(node.poll(1'100'000).has_value());
  EXPECT_EQ(node.counters().objects_before_scan, 2);
  EXPECT_EQ(node.counters().scans_without_objects, 1);
  // Objects an hour ahead (a recognizer's clock gone wrong) are not held: held,
  // they would release every scan at once. The next scan still waits for its own.
  node.on_objects(objects_for(1'100'000 + 3'600'000'000LL));
  EXPECT_EQ(node.counters().objects_without_scan, 2);
  scan.utime = 1'125'000;
  node.on_scan(scan);
  EXPECT_FALSE(node.poll(1'125'000).has_value());
  node.on_objects(objects_for(1'125'000));
  ASSERT_TRUE(node.poll(1'125'000).has_value());
  EXPECT_EQ(node.counters().scans_without_objects, 1);
  // Objects held at the end, their scan never came: counted when the node flushes.
  node.on_objects(objects_for(1'150'000));
  EXPECT_FALSE(node.poll(kFlush).has_value());
  EXPECT_EQ(node.counters().objects_without_scan, 3);
  EXPECT_EQ(node.counters().stale_objects, 1);
}

TEST(LocalizerNode, ObjectsBeforeTheFirstScanAreHeldOnlyNearIt) {
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kSlamer), w.robot.lidar.mount);
  node.on_odometry(0, {});
  node.on_objects(objects_for(5'000'000));  // 4 s after the first scan: not of a scan on its way
  node.on_objects(objects_for(1'000'000));
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  scan.utime = 1'000'000;
  node.on_scan(scan);
  std::optional<UpdateResult> first = node.poll(1'000'000);  // with its objects, at once
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(node.counters().objects_before_scan, 1);
  EXPECT_EQ(node.counters().objects_without_scan, 1);
  EXPECT_EQ(node.counters().scans_without_objects, 0);
  scan.utime = 1'025'000;  // and the next scan waits for its own
  node.on_scan(scan);
  EXPECT_FALSE(node.poll(1'025'000).has_value());
}

TEST(LocalizerNode, ASlowRecognizerIsWaitedForAsLongAsObjectsWaitHoweverManyScansThatIs) {
  const SmallWorld w;
  LocalizerOptions options = node_options(LocalizerMode::kSlamer);
  options.inputs.objects_wait = 1.0;
  LocalizerNode node(w.map, options, w.robot.lidar.mount);
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  // 120 scans at 40 Hz; each scan's objects come 0.8 s (32 scans) after it.
  constexpr int64_t kPeriod = 25'000;
  constexpr int kLag = 32;
  int released = 0;
  for (int i = 0; i < 120 + kLag; ++i) {
    const int64_t now = 1'000'000 + kPeriod * i;
    node.on_odometry(now, {});
    if (i < 120) {
      scan.utime = now;
      node.on_scan(scan, now);
    }
    if (i >= kLag) {
      node.on_objects(objects_for(now - kLag * kPeriod));
    }
    while (node.poll(now)) {
      ++released;
    }
  }
  EXPECT_EQ(released, 120);
  EXPECT_EQ(node.counters().scans_without_objects, 0);
  EXPECT_EQ(node.counters().stale_objects, 0);
  EXPECT_FALSE(node.health().objects_missing);
}

TEST(LocalizerNode, MissingRecognizerStopsTheWaitAndSaysSo) {
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kSlamer), w.robot.lidar.mount);
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  int released_at_once = 0;
  for (int i = 0; i < 80; ++i) {  // 2 s of scans and odometry, no objects at all
    scan.utime = 1'000'000 + 25'000 * i;
    node.on_odometry(scan.utime, {});
    node.on_scan(scan);
    if (node.poll(scan.utime).has_value()) {
      ++released_at_once;
    }
    while (node.poll(scan.utime + 100'000)) {
    }
  }
  EXPECT_TRUE(node.health().objects_missing);
  EXPECT_TRUE(std::isinf(node.health().objects_age));
  // After objects_timeout (1 s = 40 scans) every scan goes at once, not after objects_wait.
  EXPECT_GE(released_at_once, 38);
  EXPECT_EQ(node.counters().scans_without_objects, 80);
  // Objects again: the node waits for them again.
  scan.utime += 25'000;
  node.on_odometry(scan.utime, {});
  node.on_scan(scan);
  node.on_objects(objects_for(scan.utime));
  ASSERT_TRUE(node.poll(scan.utime).has_value());
  EXPECT_FALSE(node.health().objects_missing);
}

TEST(LocalizerNode, StaleScansAreDroppedAndTimeGoingBackRestarts) {
  const SmallWorld w;
  LocalizerOptions options = node_options(LocalizerMode::kLfm);
  LocalizerNode node(w.map, options, w.robot.lidar.mount);
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  const auto feed = [&](int64_t utime) {
    scan.utime = utime;
    node.on_odometry(utime, {});
    node.on_scan(scan);
    return node.poll(utime);
  };
  ASSERT_TRUE(feed(5'000'000).has_value());
  ASSERT_TRUE(feed(5'025'000).has_value());
  EXPECT_FALSE(feed(5'025'000).has_value());  // duplicate
  EXPECT_FALSE(feed(5'010'000).has_value());  // out of order
  EXPECT_EQ(node.counters().stale_scans, 2);
  EXPECT_EQ(node.counters().stale_odometry, 2);
  EXPECT_EQ(node.counters().resets, 0);
  // A log replayed from the top: 5 s back. The filter starts over from the initial pose.
  scan = w.scan_at({2.0, 3.0, 0.0});
  const std::optional<UpdateResult> restarted = feed(25'000);
  ASSERT_TRUE(restarted.has_value());
  EXPECT_EQ(node.counters().resets, 1);
  EXPECT_NEAR(restarted->estimate.pose.x, 2.0, 0.05);
  ASSERT_TRUE(feed(50'000).has_value());
  EXPECT_EQ(node.counters().stale_scans, 2);
}

TEST(LocalizerNode, NonFiniteInputIsRefusedNotSpread) {
  const SmallWorld w;
  LocalizerNode node(w.map, node_options(LocalizerMode::kSlamer), w.robot.lidar.mount);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(node.on_initial_pose({kNaN, 3.0, 0.0}, {0.1, 0.1, 0.1}));
  EXPECT_FALSE(node.on_initial_pose({2.0, 3.0, 0.0}, {0.1, kNaN, 0.1}));
  EXPECT_FALSE(node.on_initial_pose({2.0, 3.0, 0.0}, {0.1, 0.1}));
  node.on_odometry(1'000'000, {0.0, 0.0, 0.0});
  node.on_odometry(1'010'000, {kNaN, 0.0, 0.0});
  node.on_odometry(1'020'000, {0.0, std::numeric_limits<double>::infinity(), 0.0});
  EXPECT_EQ(node.counters().invalid_odometry, 2);
  node.on_odometry(1'030'000, {0.0, 0.0, 0.0});  // past the scan's time: it need not wait
  LaserScan scan = w.scan_at({2.0, 3.0, 0.0});
  scan.utime = 1'025'000;
  node.on_scan(scan);
  // Objects with NaN ends or probabilities next to a sound one.
  LineObjectSet objects = objects_for(scan.utime);
  objects.class_names = {"open_door", "others"};
  LineObject sound{LineKind::kPhysical, {1.0, -1.0}, {1.0, 1.0}, 20, {0.2f, 0.8f}, 1};
  LineObject nan_end = sound;
  nan_end.end.x() = kNaN;
  LineObject nan_prob = sound;
  nan_prob.probs[0] = std::numeric_limits<float>::quiet_NaN();
  objects.objects = {nan_end, sound, nan_prob};
  node.on_objects(objects);
  const std::optional<UpdateResult> result = node.poll(scan.utime);
  ASSERT_TRUE(result.has_value());
  EXPECT_NEAR(result->estimate.pose.x, 2.0, 0.05);
  EXPECT_NEAR(result->estimate.pose.y, 3.0, 0.05);
  EXPECT_EQ(result->semantic.objects.size(), 1u);  // the sound one
  for (const Particle& p : node.particles()) {
    ASSERT_TRUE(std::isfinite(p.log_weight) && std::isfinite(p.pose.x) && std::isfinite(p.pose.theta));
  }
}

// Drives 0.4 m/s along +x for 2 s with scans only; returns the last estimate.
std::optional<UpdateResult> drive_without_odometry(const SmallWorld& w, LocalizerNode* node) {
  std::optional<UpdateResult> last;
  for (int i = 0; i <= 80; ++i) {
    LaserScan scan = w.scan_at({2.0 + 0.01 * i, 3.0, 0.0});
    scan.utime = 1'000'000 + 25'000 * i;
    node->on_scan(scan);
    while (auto out = node->poll(scan.utime)) {
      last = out;
    }
  }
  return last;
}

TEST(LocalizerNode, WithoutOdometryTheParticlesFollowTheScans) {
  const SmallWorld w;
  LocalizerOptions options = node_options(LocalizerMode::kLfm);
  options.particles = 300;
  LocalizerNode node(w.map, options, w.robot.lidar.mount);
  const std::optional<UpdateResult> last = drive_without_odometry(w, &node);
  ASSERT_TRUE(last.has_value());
  EXPECT_NEAR(last->estimate.pose.x, 2.8, 0.1);
  EXPECT_NEAR(last->estimate.pose.y, 3.0, 0.1);
  EXPECT_TRUE(node.health().odometry_missing);
  EXPECT_EQ(node.counters().scans_without_odometry, 81);
  // Odometry comes back at a far-off reading: its first sample is a new reference, not a jump.
  LaserScan scan = w.scan_at({2.8, 3.0, 0.0});
  scan.utime = 3'050'000;
  node.on_odometry(3'040'000, {100.0, -50.0, 2.0});
  node.on_odometry(3'060'000, {100.0, -50.0, 2.0});
  node.on_scan(scan);
  const std::optional<UpdateResult> back = node.poll(scan.utime);
  ASSERT_TRUE(back.has_value());
  EXPECT_FALSE(node.health().odometry_missing);
  EXPECT_NEAR(back->estimate.pose.x, 2.8, 0.1);
  // The diffusion is what follows: with no_odometry_speed 0 the estimate is left behind
  // (and without the local scan match, which would follow the scans too).
  options.motion.no_odometry_speed = 0.0;
  options.motion.no_odometry_turn_rate = 0.0;
  options.recovery.local.below = 0.0;
  LocalizerNode still(w.map, options, w.robot.lidar.mount);
  const std::optional<UpdateResult> behind = drive_without_odometry(w, &still);
  ASSERT_TRUE(behind.has_value());
  EXPECT_LT(behind->estimate.pose.x, 2.3);
}

TEST(ParticleFilter, StatusSaysWhenItIsUncertainOrLost) {
  const SmallWorld w;
  LocalizerOptions options = node_options(LocalizerMode::kLfm);
  options.particles = 300;
  ParticleFilter filter(w.map, options, w.robot.lidar.mount);
  // Spread over 1 m: uncertain until the scans have pulled the particles together.
  filter.initialize({2.0, 3.0, 0.0}, {1.0, 1.0, 0.05});
  EXPECT_EQ(filter.estimate().status, LocalizerStatus::kInitializing);
  const LaserScan here = w.scan_at({2.0, 3.0, 0.0});
  const std::vector<double> sigma{0.02, 0.02, 0.01};
  std::vector<LocalizerStatus> statuses;
  for (int i = 0; i < 15; ++i) {
    statuses.push_back(filter.update(here, nullptr).estimate.status);
    filter.predict({}, {}, 0.1);  // standing still: the motion model adds no noise
  }
  EXPECT_EQ(statuses.front(), LocalizerStatus::kUncertain);
  EXPECT_EQ(statuses.back(), LocalizerStatus::kOk);
  // Kidnapped: the scans now come from the other room. Not silent: LOST after lost_after scans.
  const LaserScan elsewhere = w.scan_at({8.5, 1.2, 2.5});
  int scans_until_lost = 0;
  while (filter.update(elsewhere, nullptr).estimate.status != LocalizerStatus::kLost && scans_until_lost < 100) {
    ++scans_until_lost;
  }
  EXPECT_EQ(scans_until_lost + 1, options.status.lost_after);
  // Put back where it is: OK again at once.
  filter.initialize({8.5, 1.2, 2.5}, sigma);
  EXPECT_EQ(filter.update(elsewhere, nullptr).estimate.status, LocalizerStatus::kOk);
}

TEST(SavedPose, RoundTripsExactlyAndRejectsBadFiles) {
  SavedPose saved;
  saved.utime = 1'700'000'000'123'456;
  saved.pose = {12.345678901234567, -0.1, 3.0};
  saved.sigma = {0.05, 0.06, 0.01};
  const auto back = parse_options<SavedPose>(format_saved_pose(saved), "pose.yaml");
  EXPECT_EQ(back.utime, saved.utime);
  EXPECT_EQ(back.pose.x, saved.pose.x);
  EXPECT_EQ(back.pose.y, saved.pose.y);
  EXPECT_EQ(back.pose.theta, saved.pose.theta);
  EXPECT_EQ(back.sigma, saved.sigma);
  for (const std::string& bad : {std::string("utime: 1\npose: [1, 2]\nsigma: [0, 0, 0]\n"),
                                 std::string("utime: 1\npose: [1, 2, 3]\nsigma: [0, 0, 0]\nspeed: 4\n"),
                                 std::string("utime: 1\npose: [1, nan, 3]\nsigma: [0, 0, 0]\n"),
                                 std::string("utime: 1\npose: [1, 2, 3]\nsigma: [-1, 0, 0]\n"),
                                 std::string("utime: 1\npose: [1, 2,"), std::string("\x01\x02\xff")}) {
    try {
      parse_options<SavedPose>(bad, "pose.yaml");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const ConfigError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("pose.yaml"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  const double covariance[9] = {0.0025, 0, 0, 0, 0.0, 0, 0, 0, 0.0004};
  const std::vector<double> sigma = sigma_of_covariance(covariance);
  EXPECT_NEAR(sigma[0], 0.05, 1e-12);
  EXPECT_NEAR(sigma[1], 1e-3, 1e-12);  // floored
  EXPECT_NEAR(sigma[2], 0.02, 1e-12);
}

TEST(AtomicFile, ReplacesTheWholeFileAndFailsInOneLine) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "slamer_atomic_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "pose.yaml").string();
  write_file_atomically(path, "first, a longer content\n");
  write_file_atomically(path, "second\n");
  std::ifstream in(path);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), "second\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1)
      << "no temporary file left behind";
  try {
    write_file_atomically((dir / "missing" / "pose.yaml").string(), "x");
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("missing/pose.yaml"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slamer

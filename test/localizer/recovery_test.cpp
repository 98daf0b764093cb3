// Recovery while LOST with a kidnapping prior (particle_filter_challengers.cpp):
// the places global proposals find compete beside the tracked cloud and take
// it only once one of them has fitted clearly better for recovery.adopt_time.
// The robot stands still in the small room; for a while the scans are those
// of another place in the room (the other room's corner, 6.6 m away): for
// 1 s that is a look-alike place that fits for a moment, for 6 s a kidnapping.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "localizer/particle_filter.hpp"
#include "test/localizer/options_error.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

constexpr int64_t kScanPeriod = 25'000;  // [us] 40 Hz
const Pose2 kHome{2.0, 3.0, 0.0};
const Pose2 kElsewhere{8.5, 1.2, 2.5};

struct Scan {
  double time = 0.0;       // [s] since the first scan
  bool elsewhere = false;  // the scan was taken at kElsewhere
  Pose2 estimate;
  LocalizerStatus status = LocalizerStatus::kInitializing;
  bool adopted = false;
};

// 1 s at home, `away` seconds of scans from kElsewhere, 4 s at home again.
std::vector<Scan> stand_still(const SmallWorld& w, double adopt_time, double away) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  options.lfm.beam_step = 2;
  options.recovery.adopt_time = adopt_time;
  ParticleFilter filter(w.map, options, w.robot.lidar.mount);
  filter.initialize(kHome, {0.02, 0.02, 0.01});
  const LaserScan home = w.scan_at(kHome);
  const LaserScan elsewhere = w.scan_at(kElsewhere);
  std::vector<Scan> scans;
  const int count = static_cast<int>(std::lround((5.0 + away) * 1e6 / kScanPeriod));
  for (int k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) * kScanPeriod * 1e-6;
    const bool away_now = t >= 1.0 && t < 1.0 + away;
    LaserScan scan = away_now ? elsewhere : home;
    scan.utime = 1'000'000 + k * kScanPeriod;
    filter.predict({}, {});
    const UpdateResult r = filter.update(scan, nullptr);
    scans.push_back({t, away_now, r.estimate.pose, r.estimate.status, r.adopted});
  }
  return scans;
}

double distance(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

TEST(Recovery, APlaceThatFitsBetterForLessThanTheAdoptTimeDoesNotTakeTheCloud) {
  const SmallWorld w;
  const std::vector<Scan> scans = stand_still(w, 2.0, 1.0);
  double farthest = 0.0;
  bool lost = false;
  for (const Scan& s : scans) {
    farthest = std::max(farthest, distance(s.estimate, kHome));
    lost = lost || s.status == LocalizerStatus::kLost;
    EXPECT_FALSE(s.adopted) << "at " << s.time << " s";
  }
  EXPECT_TRUE(lost) << "1 s of another place's scans is 40 scans, twice lost_after";
  EXPECT_LT(farthest, 0.2);
  EXPECT_LT(distance(scans.back().estimate, kHome), 0.1);  // the cloud spread while LOST
  EXPECT_EQ(scans.back().status, LocalizerStatus::kOk);

  // With the proposals joining the cloud at once (adopt_time 0, as before):
  // the cloud jumps to the other place, then back once the scans come home.
  const std::vector<Scan> at_once = stand_still(w, 0.0, 1.0);
  double farthest_at_once = 0.0;
  for (const Scan& s : at_once) {
    farthest_at_once = std::max(farthest_at_once, distance(s.estimate, kHome));
  }
  EXPECT_GT(farthest_at_once, 5.0);
}

TEST(Recovery, KidnappedTheCloudMovesToTheNewPlaceAboutTheAdoptTimeAfterLost) {
  const SmallWorld w;
  const double adopt_time = 2.0;
  const std::vector<Scan> scans = stand_still(w, adopt_time, 6.0);
  double lost_at = -1.0;
  double adopted_at = -1.0;
  double ok_there_at = -1.0;
  for (const Scan& s : scans) {
    if (!s.elsewhere) {
      continue;  // the kidnapping; home again after it is the same story back
    }
    if (lost_at < 0.0 && s.status == LocalizerStatus::kLost) {
      lost_at = s.time;
    }
    if (s.adopted) {
      EXPECT_LT(adopted_at, 0.0) << "adopted twice";
      adopted_at = s.time;
    }
    if (adopted_at < 0.0) {
      EXPECT_GT(distance(s.estimate, kElsewhere), 1.0) << "there before adopting, at " << s.time << " s";
    } else {
      EXPECT_LT(distance(s.estimate, kElsewhere), 0.1) << "at " << s.time << " s";
    }
    if (lost_at > 0.0 && ok_there_at < 0.0 && s.status == LocalizerStatus::kOk) {
      ok_there_at = s.time;
    }
  }
  ASSERT_GT(lost_at, 0.0);
  ASSERT_GT(adopted_at, 0.0) << "never moved to where the scans are";
  // The challengers need some scans to find the place (6 fresh proposals a
  // scan here) and to fit it as a correct pose does, then adopt_time.
  EXPECT_GE(adopted_at - lost_at, adopt_time);
  EXPECT_LT(adopted_at - lost_at, adopt_time + 1.0);
  EXPECT_GE(ok_there_at, adopted_at) << "OK before the cloud was there";
  EXPECT_LT(ok_there_at - adopted_at, 0.5);
  // Home again (the scans come from home from 7 s on, for 4 s): found the same way.
  EXPECT_LT(distance(scans.back().estimate, kHome), 0.05);
  EXPECT_EQ(scans.back().status, LocalizerStatus::kOk);
}

TEST(RecoveryOptions, AdoptTimeAndMarginAreCheckedWithTheirKey) {
  const auto error_of = localizer_options_error;
  EXPECT_EQ(error_of("recovery: {adopt_time: 0, adopt_margin: 0.2}\n"), "");
  EXPECT_NE(error_of("recovery: {adopt_time: -1}\n").find("'recovery.adopt_time'"), std::string::npos)
      << error_of("recovery: {adopt_time: -1}\n");
  EXPECT_NE(error_of("recovery: {adopt_margin: 1.5}\n").find("'recovery.adopt_margin'"), std::string::npos)
      << error_of("recovery: {adopt_margin: 1.5}\n");
}

}  // namespace
}  // namespace slamer

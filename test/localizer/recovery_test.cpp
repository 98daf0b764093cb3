// Recovery while LOST with a kidnapping prior (particle_filter_challengers.cpp):
// the places global proposals find compete beside the tracked cloud and take
// it only once one of them has fitted clearly better for recovery.adopt_time.
// The robot stands still in the small room; for a while the scans are those
// of another place in the room (the other room's corner, 6.6 m away): for
// 1 s that is a look-alike place that fits for a moment, for 6 s a kidnapping.
// Then the probation after an adoption, in a 6 m x 3 m room: L-shaped, no
// other place looks alike; plain, its half turn does (a rival).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
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

// 1 s at home, `away` seconds of scans from kElsewhere, `back` seconds at home again.
std::vector<Scan> stand_still(const SmallWorld& w, double adopt_time, double away, double back = 4.0) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  options.lfm.beam_step = 2;
  options.recovery.adopt_time = adopt_time;
  options.recovery.probation_time = 0.0;  // the adoption alone; probation has its tests below
  ParticleFilter filter(w.map, options, w.robot.lidar.mount);
  filter.initialize(kHome, {0.02, 0.02, 0.01});
  const LaserScan home = w.scan_at(kHome);
  const LaserScan elsewhere = w.scan_at(kElsewhere);
  std::vector<Scan> scans;
  const int count = static_cast<int>(std::lround((1.0 + away + back) * 1e6 / kScanPeriod));
  for (int k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) * kScanPeriod * 1e-6;
    const bool away_now = t >= 1.0 && t < 1.0 + away;
    LaserScan scan = away_now ? elsewhere : home;
    scan.utime = 1'000'000 + k * kScanPeriod;
    filter.predict({}, {}, kScanPeriod * 1e-6);
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
  // Home for 10 s after the kidnapping: the way back is a second search, and 4 s were too
  // few for one of four challenger generators tried (5.9 m off at the end).
  const std::vector<Scan> scans = stand_still(w, adopt_time, 6.0, 10.0);
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
      // The challengers' place, refined by a local match at the adoption: 3-6 cm
      // over eight challenger generators (0.06-0.16 m without it), where
      // tracking at home is 2-2.5 cm (the map is the room at 5 cm cells).
      EXPECT_LT(distance(s.estimate, kElsewhere), 0.08) << "at " << s.time << " s";
    }
    if (lost_at > 0.0 && ok_there_at < 0.0 && s.status == LocalizerStatus::kOk) {
      ok_there_at = s.time;
    }
  }
  ASSERT_GT(lost_at, 0.0);
  ASSERT_GT(adopted_at, 0.0) << "never moved to where the scans are";
  // The challengers need some scans to find the place (6 fresh proposals a
  // scan here) and to fit it as a correct pose does, then adopt_time (up to
  // 1.9 s more over eight challenger generators).
  EXPECT_GE(adopted_at - lost_at, adopt_time);
  EXPECT_LT(adopted_at - lost_at, adopt_time + 2.5);
  EXPECT_GE(ok_there_at, adopted_at) << "OK before the cloud was there";
  EXPECT_LT(ok_there_at - adopted_at, 0.5);
  // Home again (the scans come from home from 7 s on): found the same way.
  EXPECT_LT(distance(scans.back().estimate, kHome), 0.05);
  EXPECT_EQ(scans.back().status, LocalizerStatus::kOk);
}

// A room of 6 m x 3 m at 5 cm, walls one cell thick; `corner_block`: a 2 m x
// 1.5 m block fills its far corner (an L-shaped room). Without it the room
// looks the same from (x, y, theta) and from its half turn about the centre.
SemanticMap room(bool corner_block) {
  return grid_map(120, 60, [corner_block](int x, int y) {
    return x == 0 || x == 119 || y == 0 || y == 59 || (corner_block && x >= 80 && y >= 30);
  });
}

// A 270 deg, 541-beam scan of `map` from `pose` (the sensor at the base).
LaserScan room_scan(const SemanticMap& map, const Pose2& pose) {
  RobotOptions robot;
  robot.lidar.beams = 541;
  return simulated_scan(TrueWorld(map, WorldOptions{}, "room"), robot, pose);
}

struct ProbationRun {
  double adopted_at = -1.0;         // [s] when the cloud moved to where the scans were taken
  double first_ok_after = -1.0;     // [s] the first OK after that
  double rival_since = -1.0;        // [s] the first scan, after probation_time, saying "another place"
  bool ok_later_not_there = false;  // after adopting, OK at neither place
  Pose2 end;
};

// 1 s of scans at `home`, then 14 s at `kidnapped` (the robot stands still):
// LOST, the challengers' place adopted, probation.
ProbationRun kidnap(const SemanticMap& map, const Pose2& home, const Pose2& kidnapped, const Pose2& twin,
                    double probation_time) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 300;
  options.recovery.probation_time = probation_time;
  ParticleFilter filter(map, options, {});
  filter.initialize(home, {0.02, 0.02, 0.01});
  const LaserScan at_home = room_scan(map, home);
  const LaserScan there_scan = room_scan(map, kidnapped);
  ProbationRun run;
  for (int k = 0; k < 600; ++k) {
    const double t = static_cast<double>(k) * kScanPeriod * 1e-6;
    LaserScan scan = t < 1.0 ? at_home : there_scan;
    scan.utime = 1'000'000 + k * kScanPeriod;
    filter.predict({}, {}, kScanPeriod * 1e-6);
    const UpdateResult r = filter.update(scan, nullptr);
    const PoseEstimate& e = r.estimate;
    const bool there = distance(e.pose, kidnapped) < 0.1 || distance(e.pose, twin) < 0.1;
    if (r.adopted && run.adopted_at < 0.0) {
      run.adopted_at = t;
    }
    if (run.adopted_at >= 0.0 && run.first_ok_after < 0.0 && e.status == LocalizerStatus::kOk) {
      run.first_ok_after = t;
    }
    if (run.adopted_at >= 0.0 && t > run.adopted_at + probation_time + 0.5 && run.rival_since < 0.0 &&
        std::string(e.status_reason).find("another place") != std::string::npos) {
      run.rival_since = t;
    }
    run.ok_later_not_there =
        run.ok_later_not_there || (run.adopted_at >= 0.0 && e.status == LocalizerStatus::kOk && !there);
    run.end = e.pose;
  }
  return run;
}

Pose2 half_turn(const Pose2& p) {
  return {6.0 - p.x, 3.0 - p.y, wrap_angle(p.theta + M_PI)};
}

TEST(Recovery, APlaceFoundBySearchingIsUncertainForTheProbationThenOk) {
  const SemanticMap map = room(true);
  const Pose2 home{4.8, 0.8, 2.8};
  const Pose2 kidnapped{2.5, 0.7, 1.0};  // 2.3 m away, facing the block
  const double probation = 6.0;
  const ProbationRun run = kidnap(map, home, kidnapped, kidnapped, probation);
  ASSERT_GT(run.adopted_at, 0.0) << "never moved to where the scans are";
  EXPECT_LT(distance(run.end, kidnapped), 0.05);
  // The search ends a scan or two after adopting; then probation_time of UNCERTAIN.
  EXPECT_GE(run.first_ok_after, run.adopted_at + probation);
  EXPECT_LT(run.first_ok_after, run.adopted_at + probation + 0.5);
  EXPECT_LT(run.rival_since, 0.0) << "no other place of an L-shaped room looks alike";
  EXPECT_FALSE(run.ok_later_not_there);

  // Without probation (probation_time 0, as before): OK as soon as the search ends.
  const ProbationRun before = kidnap(map, home, kidnapped, kidnapped, 0.0);
  ASSERT_GT(before.adopted_at, 0.0);
  EXPECT_LT(before.first_ok_after, before.adopted_at + 0.5);
}

TEST(Recovery, WhereAnotherPlaceLooksAlikeTheStatusStaysUncertainAfterTheProbation) {
  const SemanticMap map = room(false);
  const Pose2 home{4.8, 0.8, 2.8};
  const Pose2 kidnapped{2.5, 0.7, 1.0};
  const double probation = 6.0;
  const ProbationRun run = kidnap(map, home, kidnapped, half_turn(kidnapped), probation);
  ASSERT_GT(run.adopted_at, 0.0);
  // At one of the two places the scans fit, and never OK: the challengers hold
  // the other one as a rival from the probation's end on.
  EXPECT_TRUE(distance(run.end, kidnapped) < 0.1 || distance(run.end, half_turn(kidnapped)) < 0.1)
      << run.end.x << " " << run.end.y << " " << run.end.theta;
  EXPECT_LT(run.first_ok_after, 0.0) << "OK at " << run.first_ok_after << " s";
  EXPECT_GT(run.rival_since, 0.0);
  EXPECT_LT(run.rival_since, run.adopted_at + probation + 1.5);
}

TEST(RecoveryOptions, AdoptTimeMarginsRivalPlacesAndLateProposalsAreCheckedWithTheirKey) {
  const auto error_of = localizer_options_error;
  EXPECT_EQ(error_of("recovery: {adopt_time: 0, adopt_margin: 0.2}\n"), "");
  EXPECT_NE(error_of("recovery: {adopt_time: -1}\n").find("'recovery.adopt_time'"), std::string::npos)
      << error_of("recovery: {adopt_time: -1}\n");
  EXPECT_NE(error_of("recovery: {adopt_margin: 1.5}\n").find("'recovery.adopt_margin'"), std::string::npos)
      << error_of("recovery: {adopt_margin: 1.5}\n");
  EXPECT_NE(error_of("recovery: {probation_time: -2}\n").find("'recovery.probation_time'"), std::string::npos)
      << error_of("recovery: {probation_time: -2}\n");
  EXPECT_EQ(error_of("recovery: {rival_margin: 0, rival_places: 1}\n"), "");
  EXPECT_NE(error_of("recovery: {rival_margin: -5}\n").find("'recovery.rival_margin'"), std::string::npos)
      << error_of("recovery: {rival_margin: -5}\n");
  EXPECT_NE(error_of("recovery: {rival_places: 0}\n").find("'recovery.rival_places'"), std::string::npos)
      << error_of("recovery: {rival_places: 0}\n");
  EXPECT_EQ(error_of("recovery: {late_proposals: 0}\n"), "");
  EXPECT_NE(error_of("recovery: {late_proposals: 1.5}\n").find("'recovery.late_proposals'"), std::string::npos)
      << error_of("recovery: {late_proposals: 1.5}\n");
}

// Global localization keeping rival places (rival_places.hpp): the
// robot drives 2 m along the plain room's long side, where its half turn sees
// the same at every step. Over eight filter seeds.
struct GlobalRun {
  double ok_at = -1.0;          // [s] the first OK
  bool rival_at_end = false;    // "another place" said at the last scan
  bool ends_at_a_twin = false;  // within 0.1 m of the truth or its half turn
};

constexpr int kDriveScans = 240;  // 6 s at 40 Hz, 0.33 m/s

Pose2 driven_to(int k) {
  return {1.0 + static_cast<double>(k) * kScanPeriod * 1e-6 / 3.0, 0.8, 0.0};
}

// The scans of the drive, taken once for every seed.
std::vector<LaserScan> drive_scans(const SemanticMap& map) {
  std::vector<LaserScan> scans;
  for (int k = 0; k < kDriveScans; ++k) {
    scans.push_back(room_scan(map, driven_to(k)));
    scans.back().utime = 1'000'000 + k * kScanPeriod;
  }
  return scans;
}

GlobalRun drive_after_global(const SemanticMap& map, const std::vector<LaserScan>& scans, uint64_t seed) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kLfm;
  options.particles = 1000;
  options.lfm.beam_step = 1;
  options.seed = seed;
  ParticleFilter filter(map, options, {});
  filter.initialize_global();
  GlobalRun run;
  Pose2 odometry;
  Pose2 truth;
  PoseEstimate e;
  for (int k = 0; k < kDriveScans; ++k) {
    const double t = static_cast<double>(k) * kScanPeriod * 1e-6;
    truth = driven_to(k);
    if (k > 0) {
      const Pose2 before = odometry;
      odometry = compose(odometry, between(driven_to(k - 1), truth));
      filter.predict(before, odometry, kScanPeriod * 1e-6);
    }
    e = filter.update(scans[static_cast<std::size_t>(k)], nullptr).estimate;
    if (e.status == LocalizerStatus::kOk && run.ok_at < 0.0) {
      run.ok_at = t;
    }
    run.rival_at_end = std::string(e.status_reason).find("another place") != std::string::npos;
  }
  run.ends_at_a_twin = distance(e.pose, truth) < 0.1 || distance(e.pose, half_turn(truth)) < 0.1;
  return run;
}

TEST(GlobalLocalization, KeepingRivalPlacesTheTwinOfASymmetricRoomIsHeldAsARivalToTheEnd) {
  const SemanticMap map = room(false);
  const std::vector<LaserScan> scans = drive_scans(map);
  int rival_at_end = 0;
  int ok_ever = 0;
  int at_twin = 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const GlobalRun run = drive_after_global(map, scans, seed);
    rival_at_end += run.rival_at_end ? 1 : 0;
    ok_ever += run.ok_at >= 0.0 ? 1 : 0;
    at_twin += run.ends_at_a_twin ? 1 : 0;
  }
  std::cout << "of 8 seeds: the twin held as a rival at the end " << rival_at_end << ", OK ever " << ok_ever
            << ", ending within 0.1 m of the truth or its twin " << at_twin << "\n";
  // Measured: all 8 hold the twin as a rival after 6 s, none says OK, all end at one of
  // the two. Before rival places (rival_margin 0, 2026-12-05) none held a rival and 6 said
  // OK within 0.5 s; with them as first shipped 5 said OK in the end (each place's weight
  // summed over its particles), and with that mended, at every beam 3 did (the search had
  // ended before finding the twin: global proposals not yet moved to where the scan fits).
  EXPECT_GE(rival_at_end, 7);
  EXPECT_LE(ok_ever, 1);
  EXPECT_GE(at_twin, 7);
}

}  // namespace
}  // namespace slamer

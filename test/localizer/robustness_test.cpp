// The localizer on odometry that disagrees with the scans (issue 9): the
// status under kidnapping, a zero-increment jump and drifting odometry;
// recovery after kidnapping; global localization on demand. The small room is
// simulated with realistic odometry errors and the filter run in the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <random>

#include "common/stats/status_honesty.hpp"
#include "localizer/localizer_node.hpp"
#include "test/localizer/small_world.hpp"
#include "tools/sim/simulator.hpp"

namespace slamer {
namespace {

// Uncalibrated odometry: +-1 % wheel radii, 1 % tread, turn slip, bumps (4 deg/m).
SimOptions realistic_odometry() {
  SimOptions o;
  o.wheel_radius_error_left = 0.01;
  o.wheel_radius_error_right = -0.01;
  o.tread_error = 0.01;
  o.wheel_slip.turn_slip = 0.03;
  o.wheel_slip.turn_slip_stddev = 0.05;
  o.wheel_slip.bump_rate = 0.2;
  return o;
}

LocalizerOptions robust_options() {
  LocalizerOptions o;
  o.mode = LocalizerMode::kLfm;
  o.particles = 300;
  o.lfm.beam_step = 2;
  return o;
}

struct Step {
  double time = 0.0;   // [s] since the first scan
  double error = 0.0;  // [m] position error
  LocalizerStatus status = LocalizerStatus::kInitializing;
  double heading_error = 0.0;  // [rad]
  double fit = 0.0;
  double learned = 0.0;  // [rad/m]
  std::string reason;    // why not OK
};

// Drives the small room's path; the filter sees the simulated odometry through
// `odometry_fault` (time, true odometry -> what the filter gets) and `at_scan`
// may act on it before each scan (kidnap it, ask for global localization).
class RobustLoop : public SimulatorSink {
 public:
  using Fault = std::function<Pose2(double, const Pose2&)>;
  using Action = std::function<void(double, LocalizerNode&)>;
  using ScanFault = std::function<void(double, LaserScan*)>;
  RobustLoop(const SmallWorld& w, const LocalizerOptions& options) : node_(w.map, options, w.robot.lidar.mount) {}

  Fault odometry_fault = [](double, const Pose2& p) { return p; };
  Action at_scan = [](double, LocalizerNode&) {};
  ScanFault scan_fault = [](double, LaserScan*) {};
  std::vector<Step> steps;

  void on_scan(const LaserScan& scan, int64_t) override {
    const double t = static_cast<double>(scan.utime - first_utime()) * 1e-6;
    at_scan(t, node_);
    LaserScan seen = scan;
    scan_fault(t, &seen);
    node_.on_scan(seen);
    while (const auto out = node_.poll(std::numeric_limits<int64_t>::max())) {
      const Pose2& e = out->estimate.pose;
      steps.push_back({t, std::hypot(e.x - truth_.x, e.y - truth_.y), out->estimate.status,
                       angle_diff(e.theta, truth_.theta), out->fit, out->heading_per_metre,
                       out->estimate.status_reason});
    }
  }
  void on_encoders(const EncoderSample&) override {}
  void on_odometry(const OdometrySample& s) override {
    first_utime_ = first_utime_ < 0 ? s.utime : first_utime_;
    node_.on_odometry(s.utime, odometry_fault(static_cast<double>(s.utime - first_utime()) * 1e-6, s.pose));
  }
  void on_ground_truth(const GroundTruthSample& s) override {
    truth_ = s.pose;
    truth_utime_ = s.utime;
  }
  const Pose2& truth() const { return truth_; }
  int64_t truth_utime() const { return truth_utime_; }

 private:
  int64_t first_utime() const { return first_utime_ < 0 ? 0 : first_utime_; }
  LocalizerNode node_;
  Pose2 truth_;
  int64_t truth_utime_ = 0;
  int64_t first_utime_ = -1;
};

void drive(const SmallWorld& w, const SimOptions& sim, RobustLoop* loop, uint64_t seed = 3) {
  Simulator simulator(w.world, w.options, w.robot, sim, seed);
  while (simulator.step(*loop)) {
  }
  ASSERT_GT(loop->steps.size(), 1000u);
}

LocalizerOptions starting_at(const SmallWorld& w) {
  LocalizerOptions o = robust_options();
  o.initial_pose = w.options.start;
  o.initial_sigma = {0.05, 0.05, 0.02};
  return o;
}

// Issue 9's honesty bars (common/stats/status_honesty.hpp) over steps after `from`.
static_assert(static_cast<int>(LocalizerStatus::kOk) == static_cast<int>(ReportedStatus::kOk) &&
              static_cast<int>(LocalizerStatus::kLost) == static_cast<int>(ReportedStatus::kLost));
StatusHonesty honesty(const std::vector<Step>& steps, double from = 0.0) {
  StatusHonesty h;
  for (const Step& s : steps) {
    if (s.time >= from) {
      h.add(s.time, s.error, static_cast<ReportedStatus>(static_cast<int>(s.status)));
    }
  }
  return h;
}

TEST(Robustness, DriftingOdometryIsTrackedAndSaysOk) {
  const SmallWorld w;
  RobustLoop loop(w, starting_at(w));
  drive(w, realistic_odometry(), &loop);
  double sum = 0.0;
  double max = 0.0;
  int ok = 0;
  for (const Step& s : loop.steps) {
    sum += s.error;
    max = std::max(max, s.error);
    ok += s.status == LocalizerStatus::kOk;
  }
  // With good odometry this world gives 3 cm mean (its walls are near: heading is weakly observed).
  EXPECT_LT(sum / static_cast<double>(loop.steps.size()), 0.08);
  EXPECT_LT(max, 0.2);
  EXPECT_GT(static_cast<double>(ok) / static_cast<double>(loop.steps.size()), 0.95);
}

TEST(Robustness, KidnappedItSaysSoThenRelocalizesAndSaysOkAgain) {
  const SmallWorld w;
  LocalizerOptions options = starting_at(w);
  // The drive lasts 32 s and the filter is right again 9.5-11.7 s in (simulator
  // seeds 1-9): the shipped 20 s on probation would end at the drive's end, and
  // OK again would hang on the seed (4 of 9 passed before the motion model's
  // heading slip, 3 of 9 with it). 10 s leaves room (9 of 9 either way).
  options.recovery.probation_time = 10.0;
  RobustLoop loop(w, options);
  // At 6 s the filter is told, confidently, a pose 2 m and 60 deg away from the truth.
  loop.at_scan = [&](double t, LocalizerNode& node) {
    if (std::abs(t - 6.0) < 0.0125) {
      node.on_initial_pose({5.0, 5.0, 1.0}, {0.02, 0.02, 0.01});
    }
  };
  drive(w, realistic_odometry(), &loop);
  bool lost = false;
  double lost_at = -1.0;
  double back_at = -1.0;
  for (const Step& s : loop.steps) {
    if (s.time > 6.0 && !lost && s.status == LocalizerStatus::kLost) {
      lost = true;
      lost_at = s.time;
    }
    if (lost && back_at < 0.0 && s.status == LocalizerStatus::kOk) {
      back_at = s.time;
    }
  }
  ASSERT_TRUE(lost);
  EXPECT_LT(lost_at - 6.0, 2.0);  // LOST within 2 s
  ASSERT_GT(back_at, 0.0) << "never relocalized";
  const StatusHonesty h = honesty(loop.steps);
  EXPECT_EQ(h.far_after_grace_ok(), 0);
  EXPECT_LT(h.close_lost(), h.close() / 100 + 1);
  // Once back it is right: every OK after the kidnapping within 0.2 m, and the end within 0.1 m.
  for (const Step& s : loop.steps) {
    if (s.time > 6.0 && s.status == LocalizerStatus::kOk) {
      EXPECT_LT(s.error, 0.2) << "OK at " << s.time << " s while " << s.error << " m off";
    }
  }
  EXPECT_LT(loop.steps.back().error, 0.1);
  EXPECT_EQ(loop.steps.back().status, LocalizerStatus::kOk);
}

// What a look-alike place gives: the scan fits, but only in part, for long.
// Here 38 % of the beams end at random short ranges from 4 s on (the pose
// stays about right): the fit falls to about 0.57, half-way between
// status.fit_uncertain (0.5) and fit_sustained (0.65), which the 10-scan
// smoothing mostly takes for good enough; the fit over
// status.fit_sustained_time (10 s) does not. (With 35 % it was 0.53 while the
// 40 Hz scans spread the particles by the whole floor each; with the floor's
// share for 0.025 s the pose is closer and 35 % fits 0.61, at the bar.)
TEST(Robustness, AScanThatFitsOnlyInPartForLongSaysUncertain) {
  const SmallWorld w;
  LocalizerOptions options = starting_at(w);
  RobustLoop loop(w, options);
  std::mt19937 rng(11);
  loop.scan_fault = [&](double t, LaserScan* scan) {
    if (t < 4.0) {
      return;
    }
    std::uniform_real_distribution<float> clutter(0.3f, 1.5f);
    std::uniform_real_distribution<double> pick(0.0, 1.0);
    for (float& r : scan->ranges) {
      r = pick(rng) < 0.38 ? clutter(rng) : r;
    }
  };
  drive(w, realistic_odometry(), &loop);
  ASSERT_GT(loop.steps.back().time, 25.0);
  int ok_early = 0;
  int early = 0;
  int ok_late = 0;
  int late = 0;
  double fit_late = 0.0;
  for (const Step& s : loop.steps) {
    if (s.time > 4.0 && s.time < 8.0) {
      ++early;
      ok_early += s.status == LocalizerStatus::kOk;
    }
    if (s.time > 20.0) {
      ++late;
      ok_late += s.status == LocalizerStatus::kOk;
      fit_late += s.fit;
      EXPECT_LT(s.error, 0.5) << "at " << s.time << " s";  // tracking goes on: only the status changes
    }
  }
  fit_late /= std::max(late, 1);
  EXPECT_GT(fit_late, options.status.fit_uncertain);  // the short smoothing would say OK
  EXPECT_LT(fit_late, options.status.fit_sustained);
  EXPECT_GT(ok_early, early / 2);  // a few seconds of it: mostly still OK
  EXPECT_EQ(ok_late, 0) << "of " << late;
  std::cout << "[ measured ] fit " << fit_late << " after 20 s; OK " << ok_early << " of " << early << " in 4-8 s, "
            << ok_late << " of " << late << " after 20 s\n";
}

TEST(Robustness, ZeroIncrementWhileTurningIsAbsorbed) {
  const SmallWorld w;
  RobustLoop loop(w, starting_at(w));
  // The odometry freezes for 0.4 s during the turn at the room's end (a dropout
  // in a log): its increment over the gap is exactly zero, the robot turned.
  std::optional<Pose2> at_start;
  std::optional<Pose2> at_end;
  const double t0 = 14.6;
  const double t1 = 15.0;
  loop.odometry_fault = [&](double t, const Pose2& p) {
    if (t < t0) {
      return p;
    }
    if (!at_start) {
      at_start = p;
    }
    if (t < t1) {
      return *at_start;
    }
    if (!at_end) {
      at_end = p;
    }
    return compose(*at_start, between(*at_end, p));
  };
  drive(w, realistic_odometry(), &loop);
  ASSERT_TRUE(at_end.has_value());
  const double missed = std::abs(angle_diff(at_end->theta, at_start->theta));
  EXPECT_GT(missed, 0.3);  // the turn the odometry missed [rad]
  const StatusHonesty h = honesty(loop.steps);
  EXPECT_EQ(h.far_after_grace_ok(), 0);
  EXPECT_LT(h.close_lost(), h.close() / 100 + 1);
  for (const Step& s : loop.steps) {
    if (s.status == LocalizerStatus::kOk) {
      EXPECT_LT(s.error, 0.3) << "OK at " << s.time << " s while " << s.error << " m off";
    }
  }
  EXPECT_LT(loop.steps.back().error, 0.1);
  EXPECT_EQ(loop.steps.back().status, LocalizerStatus::kOk);
}

// From t0 to t1 the odometry reports `distort` of each true increment (e.g.
// the translation's sign lost, a turn measured short); before and after, the
// true increments, from wherever the distortion left it.
RobustLoop::Fault distorted_between(double t0, double t1, std::function<Pose2(const Pose2&)> distort) {
  struct State {
    std::optional<Pose2> last_true, reported;
  };
  auto state = std::make_shared<State>();
  return [=](double t, const Pose2& p) {
    const Pose2 step = state->last_true ? between(*state->last_true, p) : Pose2{};
    state->reported = !state->reported ? p : compose(*state->reported, t >= t0 && t < t1 ? distort(step) : step);
    state->last_true = p;
    return *state->reported;
  };
}

struct FaultRun {
  double max_error = 0.0;    // [m] from the fault's start on
  double final_error = 0.0;  // [m]
  StatusHonesty honesty;
};

FaultRun run_with_fault(const SmallWorld& w, RobustLoop::Fault fault, double from, bool local_match) {
  LocalizerOptions options = starting_at(w);
  options.recovery.local.below = local_match ? options.recovery.local.below : 0.0;
  RobustLoop loop(w, options);
  loop.odometry_fault = std::move(fault);
  drive(w, realistic_odometry(), &loop);
  FaultRun run;
  for (const Step& s : loop.steps) {
    run.max_error = s.time >= from ? std::max(run.max_error, s.error) : run.max_error;
  }
  run.final_error = loop.steps.back().error;
  run.honesty = honesty(loop.steps);
  return run;
}

// fr079's failure (issue 9): the odometry lost the sign of translation while
// the robot drove on, here for 1.5 s of the straight run (about 0.6 m the
// wrong way). The scans disagree with the prediction at once; the local scan
// match puts particles where they agree.
TEST(Robustness, OdometryThatLosesTheSignOfTranslationIsCorrectedFromTheScans) {
  const SmallWorld w;
  const auto reversed = [](const Pose2& d) { return Pose2{-d.x, -d.y, d.theta}; };
  const FaultRun with = run_with_fault(w, distorted_between(6.0, 7.5, reversed), 6.0, true);
  const FaultRun without = run_with_fault(w, distorted_between(6.0, 7.5, reversed), 6.0, false);
  std::cout << "[ measured ] sign lost 1.5 s: max error " << with.max_error << " m with the local match, "
            << without.max_error << " m without\n";
  // Here, with walls near on every side, the prediction keeps fitting above
  // recovery.local.below for a while, so the match corrects late: it keeps
  // the error under the lost bar (0.5 m) where the filter without it reaches it.
  EXPECT_LT(with.max_error, 0.4);
  EXPECT_LT(with.max_error, 0.75 * without.max_error);
  EXPECT_LT(with.final_error, 0.1);
  EXPECT_EQ(with.honesty.far_after_grace_ok(), 0);
  EXPECT_LT(with.honesty.close_lost(), with.honesty.close() / 100 + 1);
}

// The other half of fr079's failure, a turn the odometry measured short
// (reference -73 deg, odometry -46 deg at its scans 4541-4553); here the
// U-turn at the room's end measured 70 % short (wheels slipping on a pivot).
TEST(Robustness, ATurnTheOdometryMeasuredShortIsCorrectedFromTheScans) {
  const SmallWorld w;
  const auto short_turn = [](const Pose2& d) { return Pose2{d.x, d.y, 0.3 * d.theta}; };
  const FaultRun with = run_with_fault(w, distorted_between(13.0, 17.0, short_turn), 13.0, true);
  const FaultRun without = run_with_fault(w, distorted_between(13.0, 17.0, short_turn), 13.0, false);
  std::cout << "[ measured ] turn 70 % short: max error " << with.max_error << " m with the local match, "
            << without.max_error << " m without\n";
  EXPECT_LT(with.max_error, 0.2);
  EXPECT_LT(with.final_error, 0.1);
  EXPECT_EQ(with.honesty.far_after_grace_ok(), 0);
  EXPECT_LT(with.honesty.close_lost(), with.honesty.close() / 100 + 1);
  // Without the match the adaptive noise absorbs it too since LOST's global
  // proposals must hold for recovery.adopt_time before taking the cloud
  // (recovery_test.cpp); when they took it at once, the filter without the
  // match got over 2x further off than with it (this test's former bar).
  EXPECT_LT(without.max_error, 0.2);
}

TEST(Robustness, GlobalLocalizationOnDemandFindsTheRobot) {
  const SmallWorld w;
  RobustLoop loop(w, starting_at(w));
  loop.at_scan = [&](double t, LocalizerNode& node) {
    if (std::abs(t - 3.0) < 0.0125) {
      node.request_global_localization();
    }
  };
  drive(w, realistic_odometry(), &loop);
  double first_ok = -1.0;
  for (const Step& s : loop.steps) {
    if (s.time > 3.0 && first_ok < 0.0 && s.status == LocalizerStatus::kOk) {
      first_ok = s.time;
    }
    if (s.time > 3.0 && s.status == LocalizerStatus::kOk) {
      EXPECT_LT(s.error, 0.2) << "OK at " << s.time << " s while " << s.error << " m off";
    }
  }
  ASSERT_GT(first_ok, 3.0) << "never found the robot";
  EXPECT_LT(first_ok - 3.0, 10.0);
  EXPECT_LT(loop.steps.back().error, 0.1);
}

// The process is killed at `saved_at` s (its pose file holds the pose of
// then, or `saved` if given) and restarted at `restart_at` s while the robot
// drove on: a new node resumes from the file.
std::vector<Step> resume_run(const SmallWorld& w, double saved_at, double restart_at,
                             std::optional<Pose2> saved = std::nullopt) {
  const LocalizerOptions options = starting_at(w);
  RobustLoop loop(w, options);
  std::optional<std::pair<Pose2, int64_t>> file;
  loop.at_scan = [&](double t, LocalizerNode& node) {
    if (!file && t >= saved_at) {
      file = {saved.value_or(loop.truth()), loop.truth_utime()};
    }
    if (file && std::abs(t - restart_at) < 0.0125) {
      node = LocalizerNode(w.map, options, w.robot.lidar.mount);
      EXPECT_TRUE(node.resume(file->first, {0.01, 0.01, 0.005}, file->second));
    }
  };
  drive(w, realistic_odometry(), &loop);
  return loop.steps;
}

TEST(Robustness, AResumedPoseIsUncertainUntilTheScansConfirmIt) {
  const SmallWorld w;
  // Killed at 5 s, back at 8 s: the robot drove on in between.
  const std::vector<Step> steps = resume_run(w, 5.0, 8.0);
  const auto first = std::find_if(steps.begin(), steps.end(), [](const Step& s) { return s.time >= 8.0; });
  ASSERT_NE(first, steps.end());
  EXPECT_GT(first->error, 0.5) << "the robot should have moved while the localizer was down";
  EXPECT_NE(first->status, LocalizerStatus::kOk) << "a pose from before the restart is not yet evidence";
  double ok_at = -1.0;
  for (auto s = first; s != steps.end(); ++s) {
    if (s->status == LocalizerStatus::kOk) {
      ok_at = ok_at < 0.0 ? s->time : ok_at;
      EXPECT_LT(s->error, 0.2) << "OK at " << s->time << " s while " << s->error << " m off";
    }
  }
  ASSERT_GT(ok_at, 8.0) << "never confirmed";
  std::cout << "resumed " << first->error << " m off, UNCERTAIN, OK after " << ok_at - 8.0 << " s\n";
  EXPECT_LT(ok_at - 8.0, 3.0);
  EXPECT_LT(steps.back().error, 0.1);
}

TEST(Robustness, AResumedPoseTheScansDoNotConfirmHandsOverToGlobalLocalization) {
  const SmallWorld w;
  // The file says the robot is somewhere it was not (carried away while the
  // localizer was down for 1 s): the grown cloud does not cover the truth.
  const std::vector<Step> steps = resume_run(w, 4.0, 5.0, Pose2{5.0, 5.0, 2.0});
  double ok_at = -1.0;
  for (const Step& s : steps) {
    if (s.time >= 5.0 && s.status == LocalizerStatus::kOk) {
      ok_at = ok_at < 0.0 ? s.time : ok_at;
      EXPECT_LT(s.error, 0.2) << "OK at " << s.time << " s while " << s.error << " m off";
    }
  }
  ASSERT_GT(ok_at, 5.0) << "never found the robot";
  std::cout << "wrong resumed pose: found by global localization, OK after " << ok_at - 5.0 << " s\n";
  EXPECT_LT(ok_at - 5.0, 12.0);
  EXPECT_LT(steps.back().error, 0.1);
  EXPECT_EQ(steps.back().status, LocalizerStatus::kOk);
}

// Wheels slipping on a wet floor: for 3 s of the straight run the odometry
// reports 1.7x the travel (about 0.7 m too far in all). The scans hold the
// pose, and their fit stays good, so the fit alone keeps saying OK; that the
// estimate went 0.5 m less far than the wheels says one of them is wrong.
// Which, the scans cannot tell (a map that differs makes the estimate slide
// the same way), so the status says UNCERTAIN until the disagreement has
// left the 10 s window. The poses are the same either way.
TEST(Robustness, AnEstimateThatTravelsFarFromWhatTheOdometrySaysIsUncertain) {
  const SmallWorld w;
  const auto slipping = [](const Pose2& d) { return Pose2{1.7 * d.x, 1.7 * d.y, d.theta}; };
  std::vector<Step> runs[2];
  for (const bool agreement : {true, false}) {
    LocalizerOptions options = starting_at(w);
    options.status.odometry_disagreement = agreement ? 0.5 : 0.0;
    RobustLoop loop(w, options);
    loop.odometry_fault = distorted_between(6.0, 9.0, slipping);
    drive(w, realistic_odometry(), &loop);
    runs[agreement ? 0 : 1] = loop.steps;
  }
  const std::vector<Step>& with = runs[0];
  const std::vector<Step>& without = runs[1];
  ASSERT_EQ(with.size(), without.size());
  int uncertain_with = 0, uncertain_without = 0, window = 0;
  double max_error = 0.0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    EXPECT_DOUBLE_EQ(with[i].error, without[i].error) << "the status only: the same poses";
    if (with[i].time >= 9.0 && with[i].time < 16.0) {
      ++window;
      uncertain_with += with[i].status != LocalizerStatus::kOk;
      if (with[i].status == LocalizerStatus::kUncertain && without[i].status == LocalizerStatus::kOk) {
        EXPECT_EQ(with[i].reason, "the estimate has lately moved far from what the odometry measured");
      }
      uncertain_without += without[i].status != LocalizerStatus::kOk;
    }
    max_error = with[i].time >= 6.0 ? std::max(max_error, with[i].error) : max_error;
    if (with[i].time < 5.0 || with[i].time > 20.0) {  // before the slip, and once its 10 s have passed
      EXPECT_EQ(with[i].status, without[i].status) << with[i].time;
    }
  }
  std::cout << "[ measured ] wheels slipping 3 s: max error " << max_error
            << " m; not OK over 9-16 s: " << uncertain_with << " of " << window
            << " scans with the odometry agreement, " << uncertain_without << " without\n";
  EXPECT_LT(max_error, 0.4);                   // the scans held the pose (0.31 m; 0.28 with the floor per scan)
  EXPECT_LT(uncertain_without, window / 10);   // and the fit alone stays OK
  EXPECT_GT(uncertain_with, 9 * window / 10);  // the disagreement does not
}

}  // namespace
}  // namespace slamer

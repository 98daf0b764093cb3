// ParticleFilter's robustness on real odometry (issue 9): the scan-fit
// status, the adaptive motion-noise gain, global proposals while LOST and
// global localization on demand. Split from particle_filter.cpp for size.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "localizer/along_track.hpp"
#include "localizer/particle_filter_internal.hpp"

namespace slamer {

namespace {
using filter_constants::kFitSmoothing;
using filter_constants::kProposalBeams;
// Local scan match: the coarse grid (about half the LFM's sigma_hit, and 0.25 m
// at 10 m range), the beams it scores with and those its fits are counted over.
constexpr double kMatchShiftStep = 0.1;   // [m]
constexpr double kMatchTurnStep = 0.025;  // [rad]
constexpr int kMatchBeams = 90;
constexpr std::size_t kMatchFitBeams = 180;
// What the cloud covers while tracking: about 3 sigma of the motion noise at
// its largest gain over one scan at walking speed.
constexpr double kNearShift = 0.15;  // [m]
constexpr double kNearTurn = 0.075;  // [rad]
// A kept place's best pose nearby is a step of its trajectory: a Gaussian prior
// on how far it lies from the place's most likely particle (the proposal
// climb's first steps; several times the motion noise of one weighing step).
constexpr double kPlaceShiftSigma = 0.1;  // [m]
constexpr double kPlaceTurnSigma = 0.05;  // [rad]
}  // namespace

void ParticleFilter::initialize_global() {
  initialize({}, {0.0, 0.0, 0.0});
  if (proposals_->empty()) {
    return;  // a map with no free space: nothing better than where it was
  }
  for (Particle& p : particles_) {
    p.pose = proposals_->uniform(rng_);
  }
  global_ = true;
  keeping_places_ = options_.recovery.rival_margin > 0.0;
  fit_smoothed_ = 0.0;
  noise_gain_ = options_.motion.noise_gain_max;
}

void ParticleFilter::require_confirmation() {
  confirm_scans_seen_ = 0;
  confirmed_in_row_ = 0;
}

void ParticleFilter::judge(PoseEstimate* e) const {
  const StatusJudgement judged = status(*e);
  e->status = judged.status;
  e->status_reason = judged.reason;
}

ParticleFilter::StatusJudgement ParticleFilter::status(const PoseEstimate& e, bool with_slide_rules) const {
  using enum LocalizerStatus;
  if (!updated_) {
    return {kInitializing, "no scan yet"};
  }
  if (lost_ && !global_) {
    return {kLost, "the scans do not fit the map"};
  }
  if (low_likelihood_scans_ >= options_.status.lost_after) {
    return {kLost, "the scans' likelihood is below its bound"};
  }
  // The scan does not fit the map where the estimate puts it; or spread
  // particles, or a posterior resting on a handful of them (e.g. right after a
  // wide initialization: tight but not yet to be trusted); or the estimate
  // has lately travelled far from what the odometry measured.
  if (global_) {
    return {kUncertain, "localizing globally"};
  }
  if (searching_) {
    return {kUncertain, "searching (lost, or a fit poor for a while): the scans do not yet fit as at a right pose"};
  }
  if (unconfirmed_) {
    return {kUncertain, "the place a search found, not yet checked against the rest of the map"};
  }
  if (rival_ || rival_place_) {
    return {kUncertain, "another place of the map fits the scans about as well"};
  }
  if (confirm_scans_seen_ >= 0) {
    return {kUncertain, "a resumed pose the scans have not confirmed yet"};
  }
  if (fit_smoothed_ < options_.status.fit_uncertain) {
    return {kUncertain, "the scan fits the map poorly"};
  }
  if (fit_sustained_ < options_.status.fit_sustained) {
    return {kUncertain, "the scans have fitted the map poorly for a while"};
  }
  if (std::sqrt(std::max(e.covariance[0], e.covariance[4])) > options_.status.uncertain_position_sigma) {
    return {kUncertain, "the particles are spread"};
  }
  if (few_particles_carry(e)) {
    return {kUncertain, "a few particles carry the estimate"};
  }
  if (with_slide_rules && along_track_slid_) {
    return {kUncertain, "the scans have fitted a pose along the heading better for a while"};
  }
  if (with_slide_rules && odometry_disagrees()) {
    return {kUncertain, "the estimate has lately moved far from what the odometry measured"};
  }
  if (with_slide_rules && options_.status.along_track_pin && options_.status.along_track_gain > 0.0 &&
      !along_track_pinned_) {
    return {kUncertain, "no scan has pinned the position along the heading since it was last in doubt"};
  }
  return {kOk, ""};
}

bool ParticleFilter::few_particles_carry(const PoseEstimate& e) const {
  return e.ess < options_.status.uncertain_ess_fraction * static_cast<double>(particles_.size());
}

bool ParticleFilter::odometry_disagrees() const {
  const double bar = options_.status.odometry_disagreement;
  return bar > 0.0 && std::abs(agreement_.along_track()) > bar;
}

void ParticleFilter::update_along_track(const ScanPoints& points, const UpdateResult& result, int64_t utime) {
  const StatusOptions& o = options_.status;
  // Only while tracking: searching, the status says UNCERTAIN anyway.
  const bool on = o.along_track_gain > 0.0 && !global_ && !searching_ && !points.x.empty();
  const AlongTrackPreference preference =
      on ? along_track_preference(field_, points, mount_, result.estimate.pose, {}) : AlongTrackPreference{};
  const bool preferred = on && preference.gain > o.along_track_gain;
  if (!preferred || (along_track_since_ && utime < *along_track_since_)) {
    along_track_since_.reset();
    along_track_scans_ = 0;
  }
  if (preferred && !along_track_since_) {
    along_track_since_ = utime;
  }
  along_track_scans_ += preferred ? 1 : 0;
  along_track_slid_ = along_track_since_ && along_track_scans_ >= o.along_track_scans &&
                      static_cast<double>(utime - *along_track_since_) * 1e-6 >= o.along_track_time;
  // Whatever put the estimate where it is without the scans saying where
  // along the heading (a search or a jump, a posterior that rested on a
  // handful of particles, the estimate leaving the odometry, the scans
  // preferring a shifted pose) leaves that position to be pinned again: by a
  // scan that fits every shifted pose worse than the estimate by
  // along_track_gain a beam, which a corridor's scans cannot.
  if (global_ || searching_ || few_particles_carry(result.estimate) || result.matched > 0 || result.adopted ||
      odometry_disagrees() || along_track_slid_) {
    along_track_pinned_ = false;
  }
  if (on && preference.margin > o.along_track_gain) {
    along_track_pinned_ = true;
  }
}

void ParticleFilter::update_fit(double fit, const PoseEstimate& e, int64_t utime) {
  // The first scan after an initialization stands alone: a pose given by
  // hand is no evidence that the scans fit there.
  fit_smoothed_ = fresh_ ? fit : fit_smoothed_ + kFitSmoothing * (fit - fit_smoothed_);
  // In time, not scans: the same evidence from a 5 Hz and a 40 Hz scanner.
  const double dt = last_fit_utime_ ? std::clamp(static_cast<double>(utime - *last_fit_utime_) * 1e-6, 0.0,
                                                 options_.status.fit_sustained_time)
                                    : 0.0;
  last_fit_utime_ = utime;
  fit_sustained_ += (1.0 - std::exp(-dt / options_.status.fit_sustained_time)) * (fit - fit_sustained_);
  fresh_ = false;
  low_fit_scans_ = fit_smoothed_ < options_.status.fit_lost ? low_fit_scans_ + 1 : 0;
  if (low_fit_scans_ >= options_.status.lost_after) {
    lost_ = true;
    searching_ = true;
  }
  // Nor does a right pose sustain a fit this poor (on aces, csail and fr079 tracked from the
  // reference, 0.74 at the least): search from here, not only once LOST. Kidnapped on aces (a
  // scan every 3 s) the cloud fitted 0.3-0.44, above fit_lost, and drifted to a wrong place.
  if (!global_ && fit_sustained_ < options_.status.fit_uncertain) {
    searching_ = true;
  }
  const bool fits = fit_smoothed_ >= options_.status.fit_uncertain;
  if (fits) {
    lost_ = false;
  }
  const bool together =
      std::sqrt(std::max(e.covariance[0], e.covariance[4])) <= options_.status.uncertain_position_sigma;
  if ((global_ || searching_) && fit_smoothed_ >= options_.status.fit_confirm && together) {
    global_ = false;
    searching_ = false;
    fit_sustained_ = fit_smoothed_;  // the confirmation is the evidence so far
    if (jumped_ && options_.recovery.probation_time > 0.0) {
      probation_until_ = utime + static_cast<int64_t>(options_.recovery.probation_time * 1e6);
    }
    jumped_ = false;
  }
  if (confirm_scans_seen_ >= 0) {
    ++confirm_scans_seen_;
    confirmed_in_row_ = fits && together ? confirmed_in_row_ + 1 : 0;
    if (confirmed_in_row_ >= options_.resume.confirm_scans) {
      confirm_scans_seen_ = -1;  // the scans say the guess was right
    } else if (confirm_scans_seen_ >= options_.resume.confirm_within || lost_) {
      // The guess was wrong: search the whole map, keeping the cloud as the
      // first hypothesis (proposals replace its least likely particles).
      confirm_scans_seen_ = -1;
      global_ = true;
      keeping_places_ = options_.recovery.rival_margin > 0.0;
      noise_gain_ = options_.motion.noise_gain_max;
      return;
    }
  }
  // Motion noise from how well the prediction explained this scan.
  const double deficit =
      (options_.status.fit_expected - fit) / std::max(options_.status.fit_expected - options_.status.fit_lost, 1e-6);
  noise_gain_ = 1.0 + (options_.motion.noise_gain_max - 1.0) * std::clamp(deficit, 0.0, 1.0);
}

std::vector<Pose2> ParticleFilter::climbed_proposals(const ScanPoints& points, int keep) {
  if (keep < 1 || options_.recovery.candidates < 1 || proposals_->empty()) {
    return {};
  }
  std::vector<Pose2> poses =
      proposals_->propose(field_, points, mount_, options_.recovery.candidates, keep, kProposalBeams, rng_);
  // Each to where the scan fits best near it: a random pose is some way off
  // the pose it stands for, and weighed there it loses tens of nats to a
  // cloud the scans have refined, so a place the search came upon later was
  // never held (the twin of a symmetric room at every beam, in 3 of 8 seeds).
  for (Pose2& p : poses) {
    p = climb_locally(field_, points, mount_, p, kMatchShiftStep, 2.0 * kMatchTurnStep, kProposalBeams);
  }
  return poses;
}

void ParticleFilter::inject(const ScanPoints& points, UpdateResult* result) {
  const int keep = static_cast<int>(options_.recovery.fraction * static_cast<double>(particles_.size()));
  const std::vector<Pose2> poses = climbed_proposals(points, keep);
  replace_least_likely(poses);
  result->injected = static_cast<int>(poses.size());
}

void ParticleFilter::propose_late(const ScanPoints& points, UpdateResult* result) {
  const int keep = static_cast<int>(options_.recovery.late_proposals * options_.recovery.fraction *
                                    static_cast<double>(particles_.size()));
  const std::vector<Pose2> poses = climbed_proposals(points, keep);
  if (poses.empty()) {
    return;
  }
  // The search ends once one place fits and is compact, which on Wean log 3
  // (seed 7) came while the robot still stood at its start, with no place
  // within 2.7 m of home among the eight: nothing proposed after that, and a
  // look-alike 14.5 m west was left alone and said OK. Margin behind the
  // best, a late place is kept only if it fits the scans better from then on.
  const double best = places_of(particles_, place_options()).front().log_weight;
  replace_least_likely(poses, best - options_.recovery.rival_margin);
  result->injected = static_cast<int>(poses.size());
}

double ParticleFilter::turn_during_sweep(const LaserScan& scan) const {
  if (!increment_ || !last_fit_utime_ || scan.utime <= *last_fit_utime_ || scan.ranges.size() < 2) {
    return 0.0;
  }
  const double turn_rate =
      std::abs(increment_->rot1 + increment_->rot2) / (static_cast<double>(scan.utime - *last_fit_utime_) * 1e-6);
  return turn_rate * scan.beam_time(scan.ranges.size() - 1);
}

Pose2 ParticleFilter::refined_place(const Pose2& place, const ScanPoints& points) const {
  // Twice the nearby window: standing still, the adopted place was 0.06-0.16 m
  // off where the scans fit best (Recovery tests, over challenger generators).
  // The search's grid holds the place itself, so the match fits at least as well.
  return slamer::match_locally(field_, points, mount_, place,
                               {2.0 * kNearShift, 2.0 * kNearTurn, kMatchShiftStep / 2.0, kMatchTurnStep,
                                static_cast<int>(kMatchFitBeams)})
      .pose;
}

void ParticleFilter::score_places(const std::vector<Place>& places, const std::vector<double>& log_likelihood,
                                  const PreparedScan& beams, const PreparedObjects& objects) {
  // A place's weight summed over its particles depends on how near the best
  // pose its cloud happens to be: after the search in a symmetric room one
  // twin's cloud was 0.5 m off along the room (13 nats a scan below the best
  // pose), the other's 0.01 m, and the scans dropped the right place. At its
  // best pose nearby (the profile likelihood: the local match's window around
  // its most likely particle) each place is scored by the scan, and the less
  // likely half of its particles move there, so its cloud follows. The match's
  // offset is priced (kPlaceShiftSigma): free to move 0.5 m at each weighing, a
  // rival on Wean log 1 slid back along its corridor scan after scan and stood
  // still at its look-alike spot while the robot drove 8 m, fitting about as
  // well as home, overtook it at scan 405 and ended 18 m away (seed 2).
  std::normal_distribution<double> shift(0.0, kMatchShiftStep / 2.0);
  std::normal_distribution<double> turn(0.0, kMatchTurnStep / 2.0);
  std::vector<double> totals;
  for (const Place& place : places) {
    std::vector<std::size_t> members = place.members;
    std::sort(members.begin(), members.end(),
              [&](std::size_t a, std::size_t b) { return particles_[a].log_weight > particles_[b].log_weight; });
    const std::size_t best = *std::max_element(members.begin(), members.end(), [&](std::size_t a, std::size_t b) {
      return log_likelihood[a] < log_likelihood[b];
    });
    const Pose2 matched = slamer::match_locally(field_, beams.points, mount_, particles_[best].pose, {}).pose;
    const Pose2 off = between(particles_[best].pose, matched);
    const double off_prior = 0.5 * (off.x * off.x + off.y * off.y) / (kPlaceShiftSigma * kPlaceShiftSigma) +
                             0.5 * off.theta * off.theta / (kPlaceTurnSigma * kPlaceTurnSigma);
    const double at_match = beams_log_likelihood(matched, beams) + objects_weight(matched, objects) - off_prior;
    totals.push_back(place.log_weight + std::max(log_likelihood[best], at_match));
    if (at_match <= log_likelihood[best]) {
      continue;
    }
    for (std::size_t k = members.size() / 2; k < members.size(); ++k) {
      Particle& p = particles_[members[k]];
      const double prior = p.log_weight - log_likelihood[members[k]];
      p.pose = {matched.x + shift(rng_), matched.y + shift(rng_), wrap_angle(matched.theta + turn(rng_))};
      p.log_weight = prior + beams_log_likelihood(p.pose, beams) + objects_weight(p.pose, objects);
    }
  }
  rescore_places(&particles_, places, totals);
}

void ParticleFilter::match_locally(const PreparedScan& beams, const PreparedObjects& objects, double sweep_turn,
                                   UpdateResult* result) {
  const ScanPoints& points = beams.points;
  const LocalMatchOptions& o = options_.recovery.local;
  const int count = static_cast<int>(o.fraction * static_cast<double>(particles_.size()));
  // Only while tracking: the last scans fitted, so the cloud was right and
  // what this scan disagrees with is the odometry since. A cloud already
  // wrong (kidnapped, lost, searching) is the global proposals' work: near a
  // wrong pose, the best local fit is a wrong place too.
  const bool tracking = updated_ && !global_ && !lost_ && !searching_ && confirm_scans_seen_ < 0 &&
                        fit_smoothed_ >= options_.status.fit_uncertain;
  // A scan taken while turning fast is bent (each beam from where the sensor
  // was then): bent by more than the search's heading step, its best match
  // is a compromise that fits the bend, not the robot's pose.
  if (o.below <= 0.0 || count < 1 || !tracking || points.x.empty() || sweep_turn > kMatchTurnStep) {
    return;
  }
  const std::size_t step = std::max<std::size_t>(1, points.x.size() / kMatchFitBeams);
  const Pose2 predicted = estimate().pose;
  const auto fit_at = [&](const Pose2& pose) {
    return scan_fit(*obstacles_, points, sensor_in_cells(geometry_, pose, mount_), options_.status.fit_distance, step);
  };
  const double fit_before = fit_at(predicted);
  if (fit_before >= o.below) {
    return;  // the odometry explained this scan: nothing to correct
  }
  // Only a match clearly better than the best pose the cloud itself reaches
  // (about its spread while tracking) says the odometry failed; where that
  // fits about as well (a corridor, a scan an unmapped object covers in part)
  // the odometry is the judge.
  const LocalMatch match = slamer::match_locally(field_, points, mount_, predicted,
                                                 {o.shift, o.turn, kMatchShiftStep, kMatchTurnStep, kMatchBeams});
  const double fit_after = fit_at(match.pose);
  if (fit_after < fit_before + o.gain || fit_after < options_.status.fit_confirm) {
    return;  // and it must fit as well as a correct pose does
  }
  // SLAMER: unless the recognized objects speak against it more than the
  // beams for it. Objects the map lacks can make a wrong pose fit the scan
  // better (suite world 102006: 0.24 m along a corridor, fit 0.66 -> 0.78,
  // beams +0.4 nats, objects -1.4), and the particles put there stayed, held
  // by the objects, 0.15 m off and LOST to the end. The beams alone do not
  // judge: the fit counts the beams near a wall, robust to what the map
  // lacks, and LFM's likelihood of every beam disagreed with it on world
  // 102003 to its cost.
  const double objects_for = objects_weight(match.pose, objects) - objects_weight(predicted, objects);
  if (objects_for < 0.0 &&
      objects_for + beams_log_likelihood(match.pose, beams) - beams_log_likelihood(predicted, beams) < 0.0) {
    return;
  }
  const LocalMatch near = slamer::match_locally(
      field_, points, mount_, predicted, {kNearShift, kNearTurn, kMatchShiftStep / 2.0, kMatchTurnStep, kMatchBeams});
  const double fit_near = fit_at(near.pose);
  if (fit_after < fit_near + o.gain) {
    return;
  }
  // Another place in the window that fits about as well is as likely: if it
  // too fits clearly better than near the prediction, half the particles go
  // there and the next scans decide (with few beams the two often differ by
  // a beam or two: fr079 at 60 beams, where the odometry lost the sign of
  // translation, lost track when only a clear winner was taken); if not, the
  // scan does not say the odometry failed.
  std::vector<Pose2> centres{match.pose};
  const double fit_runner_up = fit_at(match.runner_up);
  if (fit_after < fit_runner_up + o.gain) {
    if (fit_runner_up < std::max(fit_near + o.gain, options_.status.fit_confirm)) {
      return;
    }
    centres.push_back(match.runner_up);
  }
  // Around each, within the grid's step, so the full model can refine it.
  std::normal_distribution<double> shift(0.0, kMatchShiftStep / 2.0);
  std::normal_distribution<double> turn(0.0, kMatchTurnStep / 2.0);
  std::vector<Pose2> poses;
  for (int k = 0; k < count; ++k) {
    const Pose2& c = centres[static_cast<std::size_t>(k) % centres.size()];
    poses.push_back({c.x + shift(rng_), c.y + shift(rng_), wrap_angle(c.theta + turn(rng_))});
  }
  replace_least_likely(poses);
  result->matched = count;
}

void ParticleFilter::replace_least_likely(std::vector<Particle>* set, const std::vector<Pose2>& poses,
                                          std::optional<double> log_weight) {
  std::vector<Particle>& particles = *set;
  const std::size_t n = std::min(poses.size(), particles.size());
  if (n == 0) {
    return;
  }
  std::vector<std::size_t> order(particles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](std::size_t a, std::size_t b) { return particles[a].log_weight < particles[b].log_weight; });
  const double best = std::max_element(particles.begin(), particles.end(), [](const Particle& a, const Particle& b) {
                        return a.log_weight < b.log_weight;
                      })->log_weight;
  for (std::size_t k = 0; k < n; ++k) {
    particles[order[k]] = {poses[k], log_weight.value_or(best)};
  }
}

}  // namespace slamer

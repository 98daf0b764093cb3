// ParticleFilter's recovery while LOST (issue 9): a kidnapping prior for the
// global proposals.
//
// Proposals from the whole map (global_proposals.hpp) used to replace the
// tracked cloud's least likely particles with the best one's weight, so a
// single scan decided: the place that fitted that scan best won. Where the
// robot really is, the map often explains the scan worst (that is why the
// filter got LOST: furniture the map lacks, a door the map has closed), while
// in a building of repeated rooms a look-alike place explains it well. On
// suite seed 3 (issue 11's generated worlds) LFM lost track on 8 of 20
// worlds; on 4 of them (103004, 103010, 103011, 103017) it was 6-12 cm with no
// proposals at all instead of 0.2-4.7 m: the tracked cloud found its own way
// back, where the proposals had taken it to a look-alike place.
//
// Now the proposals compete in a cloud of their own (the challengers: the
// recovery.fraction share of the particle count, a fifth of them fresh from
// the map each scan), moved by the same odometry and weighted by the same
// model. The tracked cloud, its motion noise at the largest gain, goes on
// meanwhile. Only once the challengers' best place has been the same place
// (it moves with the odometry) and fitted the scans as well as a correct pose
// does (status.fit_confirm) and recovery.adopt_margin better than the tracked
// cloud, for recovery.adopt_time, does the tracked cloud move there, its mean
// onto the best fit of a local match around the place (refined_place: once,
// about 1 ms, BM_RefineAdoptedPlace; the challengers' sample alone left it 0.06-0.16 m off).
//
// Probation: the first place a search finds may be a look-alike (suite world
// 103007, LFM seed 2: adopted 12 m off, then OK for 22 s; the right place
// fitted as well or better). After an adoption, once the search ends, the
// status is UNCERTAIN for recovery.probation_time while the challengers go on,
// now only away from the estimate; after it, a place they hold that fits as a
// correct pose does and within adopt_margin as well as the estimate (a rival)
// keeps it UNCERTAIN and the probation going. (After a search the tracked
// cloud ended by itself, or a global localization, there is none: their
// rivals cost the Wean logs 12-39 s of settling.) On probation the cloud is
// never moved, and the challengers draw from their own generator, so the
// tracked cloud's draws do not depend on them (its poses change only through
// the odometry correction, which learns from OK scans alone).
#include <algorithm>
#include <cmath>

#include "localizer/particle_filter_internal.hpp"
#include "localizer/scan_fit.hpp"

namespace slamer {

namespace {
using filter_constants::kFitSmoothing;
using filter_constants::kProposalBeams;
constexpr int kFreshShare = 5;  // 1/5 of the challengers replaced each scan: the rest remember
// The best challenger is "the same place" as at the last scan when this close
// to where that one went: the cloud's own spread, far below a look-alike
// place's distance (a room or a corridor bay away).
constexpr double kSamePlaceShift = 0.5;  // [m]
constexpr double kSamePlaceTurn = 0.3;   // [rad]
constexpr double kMaxScanGap = 0.5;      // [s] a 2 Hz scanner's period

// One place: within the cloud's own spread of each other.
bool close_by(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x - b.x, a.y - b.y) < kSamePlaceShift && std::abs(angle_diff(a.theta, b.theta)) < kSamePlaceTurn;
}
}  // namespace

void ParticleFilter::end_challenge() {
  challengers_.clear();
  challenger_track_.reset();
  challenger_fit_ = 0.0;
  challenger_held_ = 0.0;
  challenger_utime_.reset();
  rival_ = false;
}

void ParticleFilter::compete(const PreparedScan& beams, const PreparedObjects& objects, int64_t utime,
                             UpdateResult* result) {
  const auto size = static_cast<std::size_t>(options_.recovery.fraction * static_cast<double>(particles_.size()));
  if (size < 1 || options_.recovery.candidates < 1 || proposals_->empty() || beams.points.x.empty()) {
    return;
  }
  const int fresh = challengers_.empty() ? static_cast<int>(size) : std::max(1, static_cast<int>(size) / kFreshShare);
  std::vector<Pose2> poses = proposals_->propose(field_, beams.points, mount_, options_.recovery.candidates, fresh,
                                                 kProposalBeams, challenger_rng_);
  // On probation (tracking again after an adoption) they look for another place
  // than the estimate's: there they would only follow the tracked cloud.
  const Pose2& tracked = result->estimate.pose;
  const bool probation = !lost_ && !searching_;
  if (probation) {
    std::erase_if(poses, [&](const Pose2& p) { return close_by(p, tracked); });
    std::erase_if(challengers_, [&](const Particle& c) { return close_by(c.pose, tracked); });
  }
  const double joining =
      challengers_.empty()
          ? 0.0
          : std::max_element(challengers_.begin(), challengers_.end(), [](const Particle& a, const Particle& b) {
              return a.log_weight < b.log_weight;
            })->log_weight;
  std::vector<Pose2> replacing;
  for (const Pose2& pose : poses) {
    if (challengers_.size() < size) {
      challengers_.push_back({pose, joining});
    } else {
      replacing.push_back(pose);
    }
  }
  replace_least_likely(&challengers_, replacing);
  // On probation the tracked cloud is as it would be without them (the odometry correction learns).
  result->injected = probation ? 0 : static_cast<int>(poses.size());
  if (challengers_.empty()) {
    rival_ = false;
    return;
  }

  for (Particle& c : challengers_) {
    c.log_weight += beams_log_likelihood(c.pose, beams) + objects_weight(c.pose, objects);
  }
  normalize(&challengers_);
  // The place: the most likely challenger near where the place was (moved
  // by the odometry since), as long as any challenger is still there, so a
  // fresh proposal that wins one scan does not end it; else the most likely one.
  const auto near_track = [&](const Pose2& p) { return challenger_track_ && close_by(p, *challenger_track_); };
  const Particle* best = nullptr;
  const Particle* best_near = nullptr;
  for (const Particle& c : challengers_) {
    if (best == nullptr || c.log_weight > best->log_weight) {
      best = &c;
    }
    if (near_track(c.pose) && (best_near == nullptr || c.log_weight > best_near->log_weight)) {
      best_near = &c;
    }
  }
  const bool same_place = best_near != nullptr;
  const Pose2 place = same_place ? best_near->pose : best->pose;
  const double fit =
      scan_fit(*obstacles_, beams.points, sensor_in_cells(geometry_, place, mount_), options_.status.fit_distance);
  // At most kMaxScanGap a scan: one scan after a gap in the log is one scan of evidence, not seconds.
  const double dt = challenger_utime_ && utime > *challenger_utime_
                        ? std::min(static_cast<double>(utime - *challenger_utime_) * 1e-6, kMaxScanGap)
                        : 0.0;
  challenger_utime_ = utime;
  challenger_track_ = place;
  challenger_fit_ = same_place ? challenger_fit_ + kFitSmoothing * (fit - challenger_fit_) : fit;
  const bool better = !probation && same_place && challenger_fit_ >= options_.status.fit_confirm &&
                      challenger_fit_ >= fit_smoothed_ + options_.recovery.adopt_margin;
  challenger_held_ = better ? challenger_held_ + dt : 0.0;
  // On probation: a place that fits as a correct pose does and about as well
  // as the estimate is a rival.
  rival_ = probation && same_place && challenger_fit_ >= options_.status.fit_confirm &&
           challenger_fit_ >= fit_smoothed_ - options_.recovery.adopt_margin;

  if (challenger_held_ >= options_.recovery.adopt_time) {
    // The whole cloud moves: the tracked place has been the worse
    // explanation for adopt_time. The status stays UNCERTAIN (searching_)
    // until the cloud, now there, fits as a correct pose does.
    std::vector<Particle> there;
    for (const Particle& c : challengers_) {
      if (near_track(c.pose)) {  // the track is the place now
        there.push_back(c);
      }
    }
    normalize(&there);
    particles_ = resampled(there, particles_.size(), rng_);
    // The cloud, as it is, with its mean onto the best fit near the place.
    const Pose2 shift = compose(refined_place(place, beams.points), inverse(estimate().pose));
    for (Particle& p : particles_) {
      p.pose = compose(shift, p.pose);
    }
    fit_smoothed_ = challenger_fit_;
    low_fit_scans_ = 0;
    lost_ = false;
    jumped_ = true;  // probation, from the next scan that fits there, starts UNCERTAIN
    end_challenge();
    result->adopted = true;
    result->estimate = estimate();
    result->fit = fit;
    return;
  }
  double sum_squares = 0.0;
  for (const Particle& c : challengers_) {
    sum_squares += std::exp(2.0 * c.log_weight);
  }
  if (1.0 / sum_squares < options_.resample_threshold * static_cast<double>(challengers_.size())) {
    challengers_ = resampled(challengers_, challengers_.size(), challenger_rng_);
  }
}

}  // namespace slamer

// ParticleFilter's robustness on real odometry (issue 9): the scan-fit
// status, the adaptive motion-noise gain, global proposals while LOST and
// global localization on demand. Split from particle_filter.cpp for size.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "localizer/particle_filter.hpp"

namespace slamer {

namespace {
constexpr double kFitSmoothing = 0.1;  // per scan: about 10 scans (0.25 s at 40 Hz)
constexpr int kProposalBeams = 48;     // beams a global proposal is scored with
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
  fit_smoothed_ = 0.0;
  noise_gain_ = options_.motion.noise_gain_max;
}

void ParticleFilter::require_confirmation() {
  confirm_scans_seen_ = 0;
  confirmed_in_row_ = 0;
}

LocalizerStatus ParticleFilter::status(const PoseEstimate& e) const {
  if (!updated_) {
    return LocalizerStatus::kInitializing;
  }
  if ((lost_ && !global_) || low_likelihood_scans_ >= options_.status.lost_after) {
    return LocalizerStatus::kLost;
  }
  // The scan does not fit the map where the estimate puts it; or spread
  // particles, or a posterior resting on a handful of them (e.g. right after a
  // wide initialization: tight but not yet to be trusted).
  if (global_ || searching_ || confirm_scans_seen_ >= 0 || fit_smoothed_ < options_.status.fit_uncertain ||
      fit_sustained_ < options_.status.fit_sustained ||
      std::sqrt(std::max(e.covariance[0], e.covariance[4])) > options_.status.uncertain_position_sigma ||
      e.ess < options_.status.uncertain_ess_fraction * static_cast<double>(particles_.size())) {
    return LocalizerStatus::kUncertain;
  }
  return LocalizerStatus::kOk;
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
      noise_gain_ = options_.motion.noise_gain_max;
      return;
    }
  }
  // Motion noise from how well the prediction explained this scan.
  const double deficit =
      (options_.status.fit_expected - fit) / std::max(options_.status.fit_expected - options_.status.fit_lost, 1e-6);
  noise_gain_ = 1.0 + (options_.motion.noise_gain_max - 1.0) * std::clamp(deficit, 0.0, 1.0);
}

void ParticleFilter::inject(const ScanPoints& points, UpdateResult* result) {
  const int keep = static_cast<int>(options_.recovery.fraction * static_cast<double>(particles_.size()));
  if (keep < 1 || options_.recovery.candidates < 1 || proposals_->empty()) {
    return;
  }
  const std::vector<Pose2> poses =
      proposals_->propose(field_, points, mount_, options_.recovery.candidates, keep, kProposalBeams, rng_);
  // They replace the least likely particles, with the weight of the most
  // likely one: this scan's full measurement model decides between them.
  std::vector<std::size_t> order(particles_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(poses.size()), order.end(),
                    [&](std::size_t a, std::size_t b) { return particles_[a].log_weight < particles_[b].log_weight; });
  const double best = std::max_element(particles_.begin(), particles_.end(), [](const Particle& a, const Particle& b) {
                        return a.log_weight < b.log_weight;
                      })->log_weight;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    particles_[order[k]] = {poses[k], best};
  }
  result->injected = static_cast<int>(poses.size());
}

}  // namespace slamer

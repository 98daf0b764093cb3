#include "localizer/particle_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "localizer/motion_model.hpp"
#include "localizer/particle_filter_internal.hpp"
#include "localizer/recognition_model.hpp"

namespace slamer {

namespace {

// Keeping places, the particles move and a scan weighs them once the odometry
// has moved this far or turned this much (held_motion_; AMCL's update_min_d).
constexpr double kPlaceMove = 0.2;   // [m]
constexpr double kPlaceTurn = 0.2;   // [rad]
constexpr double kClearance = 0.15;  // [m] global proposals keep the robot's centre this far from obstacles

// How far the map's distance fields must reach: the LFM's likelihood field
// and SLAMER's prior, which treats everything beyond 3 sigma_d as equally far.
double field_reach(const LocalizerOptions& options) {
  return std::max(likelihood_field_reach(options.lfm), 3.0 * options.slamer.prior_sigma);
}

// free_space_class_margins index-aligned with the map's classes (0: the common margin); a name the
// map lacks has been refused by class_map_check.
std::vector<double> class_margins(const SemanticMap& map, const LocalizerOptions& options) {
  std::vector<double> margins(map.classes.size(), 0.0);
  for (const auto& [name, margin] : options.slamer.free_space_class_margins) {
    if (const int c = map.class_index(name); c >= 0) {
      margins[static_cast<std::size_t>(c)] = margin;
    }
  }
  return margins;
}

}  // namespace

ParticleFilter::ParticleFilter(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount)
    : options_(options),
      mount_(lidar_mount),
      geometry_(map.geometry),
      obstacles_(std::make_shared<const DistanceField>(obstacle_distance_field(map, field_reach(options)))),
      field_(obstacles_, options.lfm, kDenseFieldCellsMax),
      free_distance_(std::make_shared<const DistanceField>(free_space_distance_field(map, field_reach(options)))),
      free_label_distance_(
          options.slamer.free_space_margin > 0.0 || !options.slamer.free_space_class_margins.empty()
              ? std::make_shared<const DistanceField>(free_space_distance_field(
                    map, field_reach(options), options.slamer.free_space_margin, class_margins(map, options)))
              : free_distance_),
      proposals_(std::make_shared<const GlobalProposals>(free_distance_, obstacles_, kClearance)),
      rng_(static_cast<std::mt19937::result_type>(options.seed)),
      challenger_rng_(static_cast<std::mt19937::result_type>(options.seed) ^ 0x9e3779b9u),
      correction_(options.motion.odometry_correction_memory),
      agreement_(options.status.odometry_disagreement > 0.0 ? options.status.odometry_disagreement_time : 0.0,
                 options.status.odometry_disagreement_distance) {
  if (options.particles < 1) {
    throw std::invalid_argument("the filter needs at least one particle");
  }
  grid_from_world_ = inverse(geometry_.origin);
  grid_from_world_cos_ = std::cos(grid_from_world_.theta);
  grid_from_world_sin_ = std::sin(grid_from_world_.theta);
  std::vector<DistanceField> distances = class_distance_fields(map, field_reach(options));
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    map_classes_.push_back(map.classes[c].name);
    class_distances_.push_back(std::make_shared<const DistanceField>(std::move(distances[c])));
    if (options.mode == LocalizerMode::kSlfm) {
      class_fields_.emplace_back(class_distances_.back(), options.lfm);
    }
  }
}

std::size_t ParticleFilter::map_memory_bytes() const {
  std::size_t bytes = field_.distances().memory_bytes() + field_.dense_bytes() + free_distance_->memory_bytes();
  if (free_label_distance_ != free_distance_) {
    bytes += free_label_distance_->memory_bytes();
  }
  for (const auto& field : class_distances_) {
    bytes += field->memory_bytes();
  }
  return bytes;
}

void ParticleFilter::initialize(const Pose2& mean, const std::vector<double>& sigma) {
  initialize(mean, sigma, sigma, 0.0);
}

void ParticleFilter::initialize(const Pose2& mean, const std::vector<double>& sigma,
                                const std::vector<double>& wide_sigma, double wide_fraction) {
  std::normal_distribution<double> standard(0.0, 1.0);
  particles_.assign(static_cast<std::size_t>(options_.particles), {});
  const double log_uniform = -std::log(static_cast<double>(options_.particles));
  const auto tight = static_cast<std::size_t>(std::lround((1.0 - wide_fraction) * options_.particles));
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const std::vector<double>& s = i < tight ? sigma : wide_sigma;
    particles_[i].pose = {mean.x + s[0] * standard(rng_), mean.y + s[1] * standard(rng_),
                          wrap_angle(mean.theta + s[2] * standard(rng_))};
    particles_[i].log_weight = log_uniform;
  }
  low_likelihood_scans_ = 0;
  updated_ = false;
  fit_smoothed_ = options_.status.fit_expected;
  fit_sustained_ = options_.status.fit_expected;
  last_fit_utime_.reset();
  along_track_since_.reset();
  along_track_scans_ = 0;
  along_track_slid_ = false;
  along_track_pinned_ = false;  // a pose given by hand, resumed or searched for: the scans have not placed it
  fresh_ = true;
  low_fit_scans_ = 0;
  lost_ = false;
  global_ = false;
  searching_ = false;
  confirm_scans_seen_ = -1;
  noise_gain_ = 1.0;
  end_challenge();
  jumped_ = false;
  probation_until_.reset();
  unconfirmed_ = false;
  keeping_places_ = false;
  rival_place_ = false;
  held_motion_.reset();
  held_seconds_ = 0.0;
  place_scan_due_ = false;
  increment_.reset();
  last_pose_.reset();  // the learned correction stays: it belongs to the robot, not the pose
  agreement_.reset();
  odometry_forward_.reset();
}

void ParticleFilter::predict(const Pose2& odom_from, const Pose2& odom_to, double seconds) {
  const OdometryIncrement raw = decompose(odom_from, odom_to);
  if (increment_) {  // several predictions before one update: sum them
    increment_ =
        OdometryIncrement{increment_->rot1 + increment_->rot2 + raw.rot1, increment_->trans + raw.trans, raw.rot2};
  } else if (last_pose_) {
    increment_ = raw;
  }
  odometry_forward_ = odometry_forward_.value_or(0.0) + between(odom_from, odom_to).x;
  if (keeping_places_ && !global_) {
    held_motion_ = compose(held_motion_.value_or(Pose2{}), between(odom_from, odom_to));
    held_seconds_ += seconds;
    if (std::hypot(held_motion_->x, held_motion_->y) >= kPlaceMove || std::abs(held_motion_->theta) >= kPlaceTurn) {
      move_held_particles();
      place_scan_due_ = true;
    }
  } else {
    move_particles(raw, seconds);
  }
  const OdometryIncrement u = correction_.correct(raw);
  for (Particle& c : challengers_) {
    // They search: a zero increment (the robot standing) still moves them about.
    c.pose = sample_motion(c.pose, u, options_.motion, challenger_rng_, options_.motion.noise_gain_max, seconds);
  }
  if (challenger_track_) {
    challenger_track_ = compose(*challenger_track_, between(odom_from, odom_to));
  }
}

void ParticleFilter::move_particles(const OdometryIncrement& raw, double seconds) {
  const OdometryIncrement u = correction_.correct(raw);
  for (Particle& p : particles_) {
    p.pose = sample_motion(p.pose, u, options_.motion, rng_, noise_gain_, seconds);
  }
}

void ParticleFilter::move_held_particles() {
  move_particles(decompose(Pose2{}, *held_motion_), held_seconds_);
  held_motion_.reset();
  held_seconds_ = 0.0;
}

void ParticleFilter::diffuse(double seconds) {
  if (!(seconds > 0.0)) {
    return;
  }
  std::normal_distribution<double> standard(0.0, 1.0);
  last_pose_.reset();  // no odometry to compare the estimate's turn and travel with
  increment_.reset();
  odometry_forward_.reset();
  const double position = options_.motion.no_odometry_speed * seconds;
  const double heading = options_.motion.no_odometry_turn_rate * seconds;
  for (auto [set, rng] : {std::pair{&particles_, &rng_}, std::pair{&challengers_, &challenger_rng_}}) {
    for (Particle& p : *set) {
      p.pose = {p.pose.x + position * standard(*rng), p.pose.y + position * standard(*rng),
                wrap_angle(p.pose.theta + heading * standard(*rng))};
    }
  }
}

UpdateResult ParticleFilter::update(const LaserScan& scan, const LineObjectSet* objects) {
  UpdateResult result;
  if (particles_.empty()) {
    return result;
  }
  const PreparedScan beams = prepare(scan, objects);
  const PreparedObjects prepared_objects = objects != nullptr ? prepare_objects(*objects) : PreparedObjects{};
  // Keeping places, a scan from where the last one was taken weighs nothing (held_motion_).
  const bool weigh = !keeping_places_ || global_ || !updated_ || place_scan_due_;
  place_scan_due_ = false;
  // While LOST with a cloud to keep, the proposals compete beside it
  // (compete(), after this scan's fit); globally localizing, they join it.
  if (weigh && (global_ || ((lost_ || searching_) && !(options_.recovery.adopt_time > 0.0)))) {
    inject(beams.points, &result);
  }
  // Not while places are kept: its particles replace the least likely ones,
  // a rival's, with the estimate's weight.
  if (!keeping_places_) {
    match_locally(beams, prepared_objects, turn_during_sweep(scan), &result);
  }
  if (weigh && keeping_places_ && !global_ && updated_) {
    propose_late(beams.points, &result);
  }
  // Deciding between places: each is scored at its best pose (score_places).
  const std::vector<Place> scored_places =
      weigh && keeping_places_ && !global_ ? places_of(particles_, place_options()) : std::vector<Place>{};
  std::vector<double> log_likelihood(particles_.size());
  std::vector<double> beam_part(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    beam_part[i] = beams_log_likelihood(particles_[i].pose, beams);
    log_likelihood[i] = beam_part[i] + objects_weight(particles_[i].pose, prepared_objects);
    if (weigh) {
      particles_[i].log_weight += log_likelihood[i];
    }
  }
  score_places(scored_places, log_likelihood, beams, prepared_objects);
  normalize(&particles_);
  if (keeping_places_) {
    const PlaceOptions places = place_options();
    rival_place_ = rivals_in(places_of(particles_, places), places).size() > 1;
    keeping_places_ = global_ || rival_place_;  // decided: ordinary resampling from here on
    if (!keeping_places_ && held_motion_) {
      move_held_particles();
    }
  }
  double mean_beam = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    mean_beam += std::exp(particles_[i].log_weight) * beam_part[i];
  }
  const std::size_t used_beams = beams.points.x.size();
  result.mean_log_likelihood =
      used_beams > 0 ? mean_beam / (options_.lfm.beam_weight * static_cast<double>(used_beams)) : 0.0;

  // (D) the objects' class posteriors at the most likely particle's pose.
  const auto best =
      static_cast<std::size_t>(std::max_element(log_likelihood.begin(), log_likelihood.end()) - log_likelihood.begin());
  const Pose2 best_sensor = compose(particles_[best].pose, mount_);
  std::vector<std::vector<double>> class_terms;
  objects_log_likelihood(particles_[best].pose, prepared_objects, *free_label_distance_, 0.0,
                         options_.slamer.spatial_line_ends, options_.slamer.physical_line_distance, &class_terms);
  result.semantic.utime = scan.utime;
  result.semantic.seq = scan.seq;
  result.semantic.class_names = prepared_objects.class_names;
  for (std::size_t k = 0; k < prepared_objects.objects.size(); ++k) {
    const LineObject& o = prepared_objects.objects[k].object;
    const std::vector<double> terms =
        with_unmapped_objects(class_terms[k], prepared_objects.objects[k].log_recognition,
                              prepared_objects.training_prior, options_.slamer.posterior_unmapped_probability);
    const double norm = log_sum_exp(terms);
    std::vector<float> posterior;
    for (const double t : terms) {
      posterior.push_back(static_cast<float>(std::exp(t - norm)));
    }
    result.semantic.objects.push_back({o.kind, transform_point(best_sensor, o.start),
                                       transform_point(best_sensor, o.end), o.npoints, posterior,
                                       most_likely(posterior)});
  }

  updated_ = true;
  if (used_beams > 0 && result.mean_log_likelihood < options_.status.lost_mean_log_likelihood) {
    ++low_likelihood_scans_;
  } else {
    low_likelihood_scans_ = 0;
  }
  result.estimate = estimate();
  result.fit = scan_fit(*obstacles_, beams.points, sensor_in_cells(geometry_, result.estimate.pose, mount_),
                        options_.status.fit_distance);
  if (used_beams > 0) {
    update_fit(result.fit, result.estimate, scan.utime);
  }
  // On probation after an adoption: until its time is over and no rival is left.
  const bool probation = probation_until_ && (scan.utime < *probation_until_ || rival_);
  if (!global_ && (lost_ || searching_ || probation) && options_.recovery.adopt_time > 0.0) {
    compete(beams, prepared_objects, scan.utime, &result);
  } else {
    end_challenge();
    probation_until_.reset();
  }
  unconfirmed_ = probation_until_ && scan.utime < *probation_until_;
  // A jump the filter made on purpose (adopting the challengers' place,
  // global proposals) is no disagreement with the odometry: start over.
  if (result.adopted || global_) {
    agreement_.reset();
  } else if (last_pose_ && odometry_forward_) {
    agreement_.add(scan.utime, *last_pose_, result.estimate.pose, *odometry_forward_);
  }
  odometry_forward_.reset();
  update_along_track(beams.points, result, scan.utime);
  judge(&result.estimate);
  result.noise_gain = noise_gain_;
  // Learn the odometry's heading error only from scans the filter is sure of.
  if (increment_ && last_pose_ && result.injected == 0 && result.matched == 0 && !result.adopted &&
      status(result.estimate, false).status == LocalizerStatus::kOk && result.fit >= options_.status.fit_uncertain) {
    correction_.observe(*increment_, angle_diff(result.estimate.pose.theta, last_pose_->theta));
  }
  increment_.reset();
  last_pose_ = result.estimate.pose;
  result.heading_per_metre = correction_.heading_per_metre();
  if (weigh && result.estimate.ess < options_.resample_threshold * static_cast<double>(particles_.size())) {
    resample();
    result.resampled = true;
  }
  return result;
}

PoseEstimate ParticleFilter::estimate() const {
  if (keeping_places_ && !particles_.empty()) {
    // Between two places 6 m apart the mean is in neither: the most likely place's.
    PoseEstimate e = estimate_of(&places_of(particles_, place_options()).front().members);
    if (held_motion_) {  // the particles wait for the next weighing; the estimate does not
      e.pose = compose(e.pose, *held_motion_);
    }
    return e;
  }
  return estimate_of(nullptr);
}

PoseEstimate ParticleFilter::estimate_of(const std::vector<std::size_t>* members) const {
  PoseEstimate e;
  if (particles_.empty()) {
    return e;
  }
  // Tracking (no members: every particle) the effective sample size comes out
  // of the same pass; a place's estimate needs the whole set's apart.
  const std::size_t count = members != nullptr ? members->size() : particles_.size();
  const auto particle = [&](std::size_t k) -> const Particle& {
    return particles_[members != nullptr ? (*members)[k] : k];
  };
  std::vector<double> weights;
  std::vector<double> headings;
  double sum_squares = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const Particle& p = particle(k);
    const double w = std::exp(p.log_weight);
    weights.push_back(w);
    headings.push_back(p.pose.theta);
    e.pose.x += w * p.pose.x;
    e.pose.y += w * p.pose.y;
    sum_squares += w * w;
  }
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  double all_sum = total;
  double all_squares = sum_squares;
  if (members != nullptr) {
    all_sum = 0.0;
    all_squares = 0.0;
    for (const Particle& p : particles_) {
      const double w = std::exp(p.log_weight);
      all_sum += w;
      all_squares += w * w;
    }
  }
  e.pose.x /= total;
  e.pose.y /= total;
  e.pose.theta = circular_mean(headings, weights).value_or(particle(0).pose.theta);
  for (std::size_t k = 0; k < count; ++k) {
    const Particle& p = particle(k);
    const double w = weights[k] / total;
    const double d[3] = {p.pose.x - e.pose.x, p.pose.y - e.pose.y, angle_diff(p.pose.theta, e.pose.theta)};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        e.covariance[r * 3 + c] += w * d[r] * d[c];
      }
    }
  }
  e.ess = (all_sum * all_sum) / all_squares;
  judge(&e);
  return e;
}

PlaceOptions ParticleFilter::place_options() const {
  PlaceOptions o;
  o.max_places = static_cast<std::size_t>(options_.recovery.rival_places);
  o.margin = options_.recovery.rival_margin;
  return o;
}

void ParticleFilter::normalize(std::vector<Particle>* set) {
  // In log space: the weights of a scan's worst particles underflow in linear space.
  double peak = -std::numeric_limits<double>::infinity();
  for (const Particle& p : *set) {
    peak = std::max(peak, p.log_weight);
  }
  double sum = 0.0;
  for (const Particle& p : *set) {
    sum += std::exp(p.log_weight - peak);
  }
  const double log_sum = peak + std::log(sum);
  for (Particle& p : *set) {
    p.log_weight -= log_sum;
  }
}

void ParticleFilter::resample() {
  if (keeping_places_) {
    PlaceOptions places = place_options();
    if (global_) {
      // Searching, no place is dropped: fresh proposals are spread about their
      // place and weigh tens of nats less than a cloud the scans have refined.
      places.margin = std::numeric_limits<double>::infinity();
    }
    particles_ = resample_keeping_places(particles_, places_of(particles_, places), places, particles_.size(), rng_);
    normalize(&particles_);
    return;
  }
  particles_ = resampled(particles_, particles_.size(), rng_);
}

std::vector<Particle> ParticleFilter::resampled(const std::vector<Particle>& set, std::size_t n, std::mt19937& rng) {
  std::vector<Particle> next;
  std::vector<std::size_t> all(set.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  next.reserve(n);
  systematic_draw(set, all, 0.0, 1.0, n, -std::log(static_cast<double>(n)), rng, &next);
  return next;
}

}  // namespace slamer

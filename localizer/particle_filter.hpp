// The SLAMER localizer (paper Secs. III-IV): a Rao-Blackwellized particle
// filter. Each scan: (A) particles move by the odometry increment with noise
// (Eq. (5)); (C) each is weighted by the likelihood field model over the
// beams (Eqs. (10)-(13)) and, in SLAMER mode, for every recognized object by
// sum_l Dir(c-hat; a(l)) N(d_l(x); 0, sigma_d) (Eqs. (6)-(9)), or in SLFM mode
// by per-class likelihood fields (Eqs. (16)-(17)); (D) the objects' class
// posteriors (Eq. (4)) are computed at the most likely particle's pose; (E)
// the pose is the weighted mean (circular for heading) with its covariance;
// (F) with the effective sample size below a threshold, systematic
// resampling; otherwise weights carry over. Pure: no clock, no I/O, seeded.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "common/map/distance_field.hpp"
#include "common/map/likelihood_field.hpp"
#include "common/map/semantic_map.hpp"
#include "common/semantic/objects.hpp"
#include "common/sensors/laser_scan.hpp"
#include "localizer/localizer_options.hpp"

namespace slamer {

struct Particle {
  Pose2 pose;
  double log_weight = 0.0;
};

enum class LocalizerStatus { kInitializing, kOk, kUncertain, kLost };

struct PoseEstimate {
  Pose2 pose;
  double covariance[9] = {};  // (x, y, theta), row-major
  double ess = 0.0;
  LocalizerStatus status = LocalizerStatus::kInitializing;
};

struct UpdateResult {
  PoseEstimate estimate;
  LineObjectSet semantic;            // the scan's objects in the map frame with their class posteriors
  double mean_log_likelihood = 0.0;  // per used beam, weighted over particles
  bool resampled = false;
};

class ParticleFilter {
 public:
  // Precomputes the likelihood and distance fields of the map. Throws
  // std::invalid_argument for options that cannot work (e.g. no particles).
  // Copies share the (immutable) fields.
  ParticleFilter(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount);

  void initialize(const Pose2& mean, const std::vector<double>& sigma);
  bool initialized() const { return !particles_.empty(); }
  // Moves every particle by the odometry increment from `odom_from` to `odom_to`.
  void predict(const Pose2& odom_from, const Pose2& odom_to);
  // Without odometry: moves every particle by zero-mean noise of the distance
  // and turn the robot can make in `seconds` (no_odometry_speed, _turn_rate).
  void diffuse(double seconds);
  // Weights with a scan and (SLFM, SLAMER) its recognized objects, which may be null.
  UpdateResult update(const LaserScan& scan, const LineObjectSet* objects);

  const std::vector<Particle>& particles() const { return particles_; }
  // Bytes held by the map's distance fields.
  std::size_t map_memory_bytes() const;
  const GridGeometry& geometry() const { return geometry_; }
  PoseEstimate estimate() const;

  // The per-object SLAMER log term of a pose (sum over classes of recognition
  // model x map prior), for tests and diagnostics.
  double object_log_likelihood(const Pose2& pose, const LineObject& object,
                               const std::vector<std::string>& classes) const;
  // The LFM log-likelihood of a pose over a scan's used beams (already weighted by beam_weight).
  double scan_log_likelihood(const Pose2& pose, const LaserScan& scan) const;

 private:
  struct PreparedScan;
  struct PreparedObjects;
  PreparedScan prepare(const LaserScan& scan, const LineObjectSet* objects) const;
  PreparedObjects prepare_objects(const LineObjectSet& objects) const;
  double beams_log_likelihood(const Pose2& pose, const PreparedScan& scan) const;
  double objects_log_likelihood(const Pose2& pose, const PreparedObjects& objects,
                                std::vector<std::vector<double>>* class_terms) const;
  void resample();

  LocalizerOptions options_;
  Pose2 mount_;
  GridGeometry geometry_;
  LikelihoodField field_;
  std::vector<std::string> map_classes_;
  std::vector<std::shared_ptr<const DistanceField>> class_distances_;  // SLAMER prior: per map class
  std::vector<LikelihoodField> class_fields_;                          // SLFM: per map class, sharing those
  std::shared_ptr<const DistanceField> free_distance_;                 // for recognition classes on free space
  std::vector<Particle> particles_;
  std::mt19937 rng_;
  int low_likelihood_scans_ = 0;
  bool updated_ = false;
};

}  // namespace slamer

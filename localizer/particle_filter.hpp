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
//
// Robust on real odometry (issue 9): the status rests on the scan fit at the
// estimate (scan_fit.hpp), not on the particles' spread; the motion noise
// grows as the last scan fits worse (up to noise_gain_max), has a floor and
// a heavy tail on the heading for wheel bumps and slips (motion_model.hpp);
// the odometry's systematic heading error is learned while the filter is
// sure and taken out of the increments (odometry_correction.hpp);
// while the prediction fits the scan poorly, a local scan match
// (local_match.hpp) puts some particles where the scan fits best nearby;
// after a request for global localization, each scan proposes poses from the
// whole map (global_proposals.hpp), each moved to where the scan fits near it
// (climb_locally), that replace the least likely particles,
// and the places that fit about as well are kept side by side, each with its
// share of the particles and the weight the scans gave it at its best pose
// nearby, until one leads (rival_places.hpp; meanwhile scans weigh only after
// the robot moved, and a few late proposals may add a place the search missed);
// while LOST, the proposals compete in a cloud of their own and the tracked
// cloud moves to their place only once it has fitted the scans clearly better
// for recovery.adopt_time (a kidnapping prior), so the filter relocalizes by
// itself without jumping to a look-alike place a single scan favours; it says
// OK again only once the scans fit as well as at a correct pose
// (status.fit_confirm); after moving there it stays UNCERTAIN for
// recovery.probation_time while the challengers look for another place that
// fits about as well, and as long as they hold one. It says UNCERTAIN while
// the estimate has lately moved along its heading far from what the odometry
// measured (a slide the fit cannot show; odometry_agreement.hpp), while the
// scans keep preferring a pose along the heading, and after any of those or a
// given, searched or jumped-to pose until a scan pins the position along the
// heading (along_track.hpp).
#pragma once

#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "common/map/distance_field.hpp"
#include "common/map/likelihood_field.hpp"
#include "common/map/semantic_map.hpp"
#include "common/semantic/objects.hpp"
#include "common/sensors/laser_scan.hpp"
#include "localizer/global_proposals.hpp"
#include "localizer/local_match.hpp"
#include "localizer/localizer_options.hpp"
#include "localizer/odometry_agreement.hpp"
#include "localizer/odometry_correction.hpp"
#include "localizer/rival_places.hpp"

namespace slamer {

enum class LocalizerStatus { kInitializing, kOk, kUncertain, kLost };

struct PoseEstimate {
  Pose2 pose;
  double covariance[9] = {};  // (x, y, theta), row-major
  double ess = 0.0;
  LocalizerStatus status = LocalizerStatus::kInitializing;
  const char* status_reason = "no scan yet";  // why, when not OK (a fixed text; "" when OK)
};

struct UpdateResult {
  PoseEstimate estimate;
  LineObjectSet semantic;            // the scan's objects in the map frame with their class posteriors
  double mean_log_likelihood = 0.0;  // per used beam, weighted over particles
  double fit = 0.0;                  // scan fit at the estimate (fraction of beams on the map's obstacles)
  double noise_gain = 1.0;           // motion noise multiplier the next prediction uses
  double heading_per_metre = 0.0;    // [rad/m] learned odometry heading error (OdometryCorrection)
  int injected = 0;                  // particles replaced by global proposals before weighting
  int matched = 0;                   // particles replaced around a local scan match before weighting
  bool adopted = false;              // LOST: the cloud moved to the place the challengers held (compete())
  bool resampled = false;
};

class ParticleFilter {
 public:
  // The LFM field keeps its levels row-major up to this many cells (a byte
  // each: 200 m x 200 m at 5 cm), for the beams' lookups.
  static constexpr std::size_t kDenseFieldCellsMax = std::size_t{1} << 24;

  // Precomputes the likelihood and distance fields of the map. Throws
  // std::invalid_argument for options that cannot work (e.g. no particles).
  // Copies share the (immutable) fields.
  ParticleFilter(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount);

  void initialize(const Pose2& mean, const std::vector<double>& sigma);
  // A mixture: `wide_fraction` of the particles from `wide_sigma`, the rest from `sigma`.
  void initialize(const Pose2& mean, const std::vector<double>& sigma, const std::vector<double>& wide_sigma,
                  double wide_fraction);
  // Global localization: particles uniform over the map's free space, and
  // global proposals every scan until the scan fits (status UNCERTAIN until then).
  void initialize_global();
  // After initialize(): UNCERTAIN until `resume.confirm_scans` scans in a row
  // fit the map with the particles together; not confirmed within
  // `resume.confirm_within` scans, global localization takes over. For a pose
  // that is a guess (read back after a restart), not one given by hand.
  void require_confirmation();
  bool initialized() const { return !particles_.empty(); }
  // Moves every particle by the odometry increment from `odom_from` to
  // `odom_to`, which took `seconds` (the motion noise's floor grows with it).
  void predict(const Pose2& odom_from, const Pose2& odom_to, double seconds);
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
  // The objects' part of the weight (SLAMER; 0 in the other modes) of
  // particles at `poses` for one recognized set, as update() computes it: an
  // object's term is shared between poses that put its samples in the same
  // cells. For tests and diagnostics.
  std::vector<double> objects_weights(const std::vector<Pose2>& poses, const LineObjectSet& objects) const;
  // The LFM log-likelihood of a pose over a scan's used beams (already weighted by beam_weight).
  double scan_log_likelihood(const Pose2& pose, const LaserScan& scan) const;

 private:
  struct PreparedScan;
  struct PreparedObjects;
  PreparedScan prepare(const LaserScan& scan, const LineObjectSet* objects) const;
  PreparedObjects prepare_objects(const LineObjectSet& objects) const;
  // The sensor's pose on the grid (metres from the grid's origin; what
  // compose(inverse(origin), compose(pose, mount)) gives) of a particle at
  // `pose`, with the cos and sin of its heading.
  Pose2 sensor_on_grid(const Pose2& pose, double* c, double* s) const;
  double beams_log_likelihood(const Pose2& pose, const PreparedScan& scan) const;
  // `free_space`: the distances free-space classes are scored by (Eq. (7));
  // `unmapped_probability`: Eq. (7)'s floor (log_map_prior); `spatial_line_ends`:
  // which classes leave out the end samples, `physical_line_distance`: how a physical
  // line's samples make its distance (SlamerOptions). `memo`: each object's
  // term is looked up by its samples' cells first and kept there (only for
  // one set of these arguments, objects_weight's).
  double objects_log_likelihood(const Pose2& pose, const PreparedObjects& objects, const DistanceField& free_space,
                                double unmapped_probability, SpatialLineEnds spatial_line_ends,
                                PhysicalLineDistance physical_line_distance,
                                std::vector<std::vector<double>>* class_terms, bool memo = false) const;
  // The objects' part of a particle's weight (Eq. (7) with its floor): SLAMER
  // only, 0 in the other modes. The tracked cloud and the challengers share it.
  double objects_weight(const Pose2& pose, const PreparedObjects& objects) const;
  void resample();
  // `set`'s log weights normalized to sum to one (in linear space).
  static void normalize(std::vector<Particle>* set);
  // `n` draws from `set` (normalized) by systematic resampling, weights uniform.
  std::vector<Particle> resampled(const std::vector<Particle>& set, std::size_t n, std::mt19937& rng);
  void inject(const ScanPoints& points, UpdateResult* result);
  // The best `keep` global proposals for the scan, each climbed to where it fits best nearby
  // (none when keep < 1, with no candidates, or where the map has no free space).
  std::vector<Pose2> climbed_proposals(const ScanPoints& points, int keep);
  // Keeping places after the search: a few climbed proposals join, margin
  // behind the best place, so a place the search missed can still become a
  // rival by fitting better than the best place (particle_filter_robust.cpp).
  void propose_late(const ScanPoints& points, UpdateResult* result);
  // While LOST with a tracked cloud (particle_filter_challengers.cpp): global
  // proposals in a cloud of their own, adopted only once one place has fitted
  // better than the tracked cloud for recovery.adopt_time.
  void compete(const PreparedScan& beams, const PreparedObjects& objects, int64_t utime, UpdateResult* result);
  void end_challenge();
  // The place the challengers adopt, refined: they hold a sample of poses within
  // about a proposal's spread of the place, and nothing refines it while the
  // robot stands still (particle_filter_robust.cpp).
  Pose2 refined_place(const Pose2& place, const ScanPoints& points) const;
  // Particles where the scan fits clearly better than at the prediction,
  // unless the objects weigh against it (particle_filter_robust.cpp).
  // `sweep_turn`: how far the robot turned while the scan was taken [rad].
  void match_locally(const PreparedScan& beams, const PreparedObjects& objects, double sweep_turn,
                     UpdateResult* result);
  // From the odometry since the last scan and the scan's beam timing; 0 when either is unknown.
  double turn_during_sweep(const LaserScan& scan) const;
  // Puts `poses` in place of the least likely particles, with the weight of the
  // most likely one: the scan's full measurement model then decides.
  void replace_least_likely(const std::vector<Pose2>& poses, std::optional<double> log_weight = std::nullopt) {
    replace_least_likely(&particles_, poses, log_weight);
  }
  // `log_weight`: theirs instead of the most likely one's.
  static void replace_least_likely(std::vector<Particle>* set, const std::vector<Pose2>& poses,
                                   std::optional<double> log_weight = std::nullopt);
  void update_fit(double fit, const PoseEstimate& e, int64_t utime);
  // `with_slide_rules` false: without the rules that see a slide along the
  // heading (the odometry agreement, the along-track evidence): what the
  // odometry correction learns from; its heading is not what a slide disagrees on.
  struct StatusJudgement {
    LocalizerStatus status;
    const char* reason;  // a fixed text; "" when OK
  };
  StatusJudgement status(const PoseEstimate& e, bool with_slide_rules = true) const;
  // Sets e's status and its reason.
  void judge(PoseEstimate* e) const;
  // ESS under status.uncertain_ess_fraction of the particles: the posterior rests on a handful.
  bool few_particles_carry(const PoseEstimate& e) const;
  // The estimate's travel along its heading off the odometry's by more than status.odometry_disagreement.
  bool odometry_disagrees() const;
  // The along-track evidence of this scan at the estimate (along_track.hpp).
  void update_along_track(const ScanPoints& points, const UpdateResult& result, int64_t utime);
  // The odometry increment, corrected (correction_), applied to every particle with noise.
  void move_particles(const OdometryIncrement& raw, double seconds);
  void move_held_particles();  // by held_motion_, which is then cleared
  PlaceOptions place_options() const;
  // Keeping places, after a weighed scan: each of `places` (found before it
  // weighed, their log weights then) gains the scan's likelihood at the pose
  // near its most likely particle where the scan fits best, in place of the
  // sum over its particles (particle_filter_robust.cpp).
  void score_places(const std::vector<Place>& places, const std::vector<double>& log_likelihood,
                    const PreparedScan& beams, const PreparedObjects& objects);
  // The estimate over `members` of the particles (every particle when null).
  PoseEstimate estimate_of(const std::vector<std::size_t>* members) const;

  LocalizerOptions options_;
  Pose2 mount_;
  GridGeometry geometry_;
  // inverse(geometry_.origin) and its cos and sin: the same for every particle.
  Pose2 grid_from_world_;
  double grid_from_world_cos_ = 1.0, grid_from_world_sin_ = 0.0;
  std::shared_ptr<const DistanceField> obstacles_;
  LikelihoodField field_;
  std::vector<std::string> map_classes_;
  std::vector<std::shared_ptr<const DistanceField>> class_distances_;  // SLAMER prior: per map class
  std::vector<LikelihoodField> class_fields_;                          // SLFM: per map class, sharing those
  std::shared_ptr<const DistanceField> free_distance_;                 // free cells of no class: proposals, weights
  std::shared_ptr<const DistanceField> free_label_distance_;           // the same, clear of classed cells: posteriors
  std::shared_ptr<const GlobalProposals> proposals_;
  std::vector<Particle> particles_;
  std::mt19937 rng_;
  // The challengers' draws (compete()): the tracked cloud's are then the same
  // whether or not they run, so probation changes the status (and, through
  // it, what the odometry correction learns from) only.
  std::mt19937 challenger_rng_;
  int low_likelihood_scans_ = 0;
  bool updated_ = false;
  // Scan-fit state (issue 9).
  double fit_smoothed_ = 1.0;
  bool fresh_ = true;  // no scan since initialize()
  int low_fit_scans_ = 0;
  bool lost_ = false;
  bool global_ = false;  // global localization under way
  // Since LOST or the slow fit fell below status.fit_uncertain, until the scans
  // fit as at a correct pose (status.fit_confirm):
  // proposals go on and the status stays UNCERTAIN, so a look-alike place the
  // recovery found first is not taken for the right one.
  bool searching_ = false;
  double fit_sustained_ = 1.0;  // smoothed over status.fit_sustained_time
  // Since when every scan has scored a pose along the heading better than the
  // estimate (status.along_track_gain), while tracking; unset: not now.
  std::optional<int64_t> along_track_since_;
  int along_track_scans_ = 0;      // scans since along_track_since_, this one included
  bool along_track_slid_ = false;  // for status.along_track_time and _scans or longer
  // A scan has pinned the position along the heading since it was last in
  // doubt (update_along_track()); not: UNCERTAIN.
  bool along_track_pinned_ = false;
  std::optional<int64_t> last_fit_utime_;
  // require_confirmation(): scans since, and fitting scans in a row (-1: not required).
  int confirm_scans_seen_ = -1;
  int confirmed_in_row_ = 0;
  double noise_gain_ = 1.0;
  // The challengers (compete()): their cloud, their place at the last scan
  // (their most likely particle near the place before, moved since by the
  // odometry), the scan fit there smoothed while it stays the same place, and
  // for how long it has fitted clearly better than the tracked cloud.
  std::vector<Particle> challengers_;
  std::optional<Pose2> challenger_track_;
  double challenger_fit_ = 0.0;
  double challenger_held_ = 0.0;  // [s]
  std::optional<int64_t> challenger_utime_;
  // The search moved the cloud to the challengers' place (a place the tracked
  // cloud did not find by itself): probation once it ends
  // (recovery.probation_time), UNCERTAIN until probation_until_ and while the
  // challengers, going on, hold a rival of the estimate.
  bool jumped_ = false;
  std::optional<int64_t> probation_until_;
  bool unconfirmed_ = false;  // this scan is before probation_until_
  bool rival_ = false;
  // After a global localization, until the scans have decided between the
  // places that fit (rival_places.hpp): resampling keeps them, the estimate is
  // the most likely one's, and rival_place_ while more than one is within
  // recovery.rival_margin.
  bool keeping_places_ = false;
  bool rival_place_ = false;
  // Meanwhile the particles move, and the scans weigh them, only once the
  // odometry has moved kPlaceMove or turned kPlaceTurn since the last weighing
  // (as AMCL's update_min_d and _a): a robot standing still sees the same scan
  // again, and counted each time it would add the same evidence for a place
  // at every scan (1.2 nats a scan for a look-alike on Wean log 3's first 4 s).
  std::optional<Pose2> held_motion_;
  double held_seconds_ = 0.0;  // the time held_motion_ took
  bool place_scan_due_ = false;
  OdometryCorrection correction_;
  std::optional<OdometryIncrement> increment_;  // odometry since the last update (raw), for the correction
  // The estimate at the last update: the turn the correction learns and the
  // travel the agreement compares are measured from it.
  std::optional<Pose2> last_pose_;
  // Whether the estimate moves as the odometry says (status UNCERTAIN when not),
  // and the odometry's forward travel since the last update.
  OdometryAgreement agreement_;
  std::optional<double> odometry_forward_;
};

}  // namespace slamer

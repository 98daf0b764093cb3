// Options of the SLAMER localizer (a Rao-Blackwellized particle filter over
// the pose, with the objects' classes estimated analytically; paper Sec. IV)
// and its LFM / SLFM baselines.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/map/likelihood_field.hpp"
#include "common/semantic/objects.hpp"

namespace slamer {

class ConfigReader;  // common/config/config_reader.hpp: the YAML reader stays out of this header

enum class LocalizerMode { kLfm, kSlfm, kSlamer };
// A spatial line's end samples in SLAMER's class posteriors (SlamerOptions).
enum class SpatialLineEnds { kScored, kLeftOutForFreeSpace, kLeftOut };
// How a physical line's samples make its distance to a class in SLAMER's class
// posteriors (SlamerOptions).
enum class PhysicalLineDistance { kMean, kFarthest };

// Motion model (Eq. (5)): standard deviations of the odometry increment's
// rotations and translation grow with the increment (Probabilistic Robotics
// 5.4); adapted to how well the scans fit (issue 9), with a heavy tail on the
// heading for wheel bumps and slips (motion_model.hpp); without odometry the
// particles diffuse.
struct MotionOptions {
  double alpha_rot_from_rot = 0.05;          // alpha1 [rad/rad]
  double alpha_rot_from_trans = 0.02;        // alpha2 [rad/m]
  double alpha_trans_from_trans = 0.05;      // alpha3 [m/m]
  double alpha_trans_from_rot = 0.02;        // alpha4 [m/rad]
  double noise_gain_max = 4.0;               // noise x up to this as the last scan's fit falls to status.fit_lost
  double noise_floor_trans = 0.003;          // [m] per scan x (gain - 1): spreads even a zero increment
  double noise_floor_rot = 0.003;            // [rad] per scan x (gain - 1)
  double noise_floor_interval = 0.25;        // [s] scans closer get sqrt(dt / this) of the floor (a random walk)
  double heading_slip_fraction = 0.05;       // of the particles, each scan the base moved: the heavy tail
  double heading_slip_sigma = 0.02;          // [rad] their extra heading noise (a wheel bump or slip)
  double odometry_correction_memory = 10.0;  // [m] learn the odometry's heading error over this (0: off)
  double no_odometry_speed = 0.5;            // [m/s] without odometry the particles diffuse this fast
  double no_odometry_turn_rate = 0.5;        // [rad/s]
  bool operator==(const MotionOptions&) const = default;
};

// Measurement model (LFM, Eqs. (10)-(13)), used by every mode for the beams.
struct LfmOptions : LikelihoodFieldOptions {
  int beam_step = 1;          // use every n-th beam (1: all of them)
  double beam_weight = 0.05;  // exponent on each beam's likelihood: beams are not independent
  bool operator==(const LfmOptions&) const = default;
};

// SLFM (Eqs. (16)-(17)): each beam is weighed in the likelihood field of the
// class of the object it hits. Eq. (17)'s exponential term for beams of
// unknown class, lambda exp(-lambda r) / (1 - exp(-lambda r_max)), is the same
// for every pose, so it cancels when the weights are normalized: such beams
// are left out and lambda is no option.
struct SlfmOptions {
  double support = 0.1;  // [m] a beam belongs to an object this close to it
  bool operator==(const SlfmOptions&) const = default;
};

// SLAMER (Eqs. (7)-(9)).
struct SlamerOptions {
  double dirichlet_a1 = 2.00;     // concentration of the true class (config/localizer.yaml: fitted)
  double dirichlet_a2 = 1.0;      // of the others (a1 != a2, or the recognition model says nothing)
  double prior_sigma = 0.15;      // [m] sigma_d of the map prior
  double object_weight = 5.0;     // exponent on each object's term (tuned on paper_indoor)
  int object_samples = 3;         // points along an object for its representative distance
  double min_probability = 1e-3;  // recognizer probabilities are floored before log
  // [m] in the class posteriors (SEMANTIC_OBJECTS), free space's prior counts
  // only free cells this far from every classed cell: otherwise a doorway or a
  // no-entry line, one cell from free space, is as much free space as it is a
  // door, and the prior cannot tell them apart. Not in the particle weights:
  // there it pulled the pose off doorways (README, "Calibrated across worlds").
  double free_space_margin = 0.45;
  // Map classes whose cells keep free space further off than free_space_margin
  // [m] (class posteriors). A no-entry line is invisible: the spatial line the
  // recognizer finds for it joins the corners of the walls it is anchored to,
  // up to a wall's half thickness (0.15 m) beside the map's line, more with the
  // pose error, where floor 0.45 m clear of it is only ~0.3 m away. 0.7 m is
  // 0.45 m beyond such a line (from that geometry, not fitted).
  std::map<std::string, double> free_space_class_margins = {{"no_entry_line", 0.7}};
  // In the class posteriors, which samples of a spatial line score it. Its ends
  // lie on whatever bounds its gap (walls, furniture, a door's frame), never in
  // free space: with them, free space's distance across a gap between walls was
  // ~0.3 m, and a gap beside a mapped door came out nearer the door than free
  // space. kScored: every sample, every class (the paper). kLeftOutForFreeSpace:
  // free space by the samples between the ends only, the other classes by all
  // (any object). kLeftOut: every class by the samples between the ends
  // (spatial lines only). Either alone costs a third of the no-entry lines;
  // with no_entry_line's margin above, kLeftOut keeps them (README, "False
  // doors"). The particle weights always score every sample.
  SpatialLineEnds spatial_line_ends = SpatialLineEnds::kLeftOut;
  // In the class posteriors, a physical line's distance to a class: the mean of
  // its samples' (the paper's representative distance) or the farthest
  // sample's, how far the line strays from the class. A closed door's line
  // ends where the walls beside it begin, so by the mean its two end samples
  // put it almost as near the walls as the door (0.13 m against 0 m for a
  // 0.8 m leaf), and the recognizer, which cannot tell a leaf flush with its
  // wall from the wall, decided: 35 % of the closed doors right. By the
  // farthest sample the leaf is 0.4 m from any wall, and a wall that merely
  // ends at a door is far from it (README, "Closed doors"). The particle
  // weights keep the mean.
  PhysicalLineDistance physical_line_distance = PhysicalLineDistance::kFarthest;
  // Eq. (7) in the particle weights as a mixture: with this probability an
  // object is one the map lacks (furniture added, a door moved), whose prior
  // does not depend on the pose, as LFM's z_rand does for beams. Without it an
  // unmapped object recognized as a wall pulls the pose onto the nearest mapped
  // wall. 0 is the paper's prior; 0.135 (exp(-2)) puts the floor where the
  // Gaussian is at 2 sigma. Not in the class posteriors: there a floor would
  // let the recognizer's false doors stand against the map.
  double unmapped_probability = 0.135;
  // Eq. (7) in the class posteriors as a mixture (with_unmapped_objects): with
  // this probability an object is not the map's, and then its class follows the
  // training prior instead of the map. Without it an object the map knows nothing
  // of (every class's distance saturated, e.g. added furniture) took the class
  // the divided-out training prior favours most, the rarest: closed doors. Small,
  // so that the map still outweighs a confident recognizer where it has a class
  // (0.135 here lost half the no-entry lines). 0.01 chosen on suite seed 3
  // (README, "False doors").
  double posterior_unmapped_probability = 0.01;
  // The classes the recognizer emits (its config's `classes`, in LINE_OBJECTS).
  std::vector<std::string> recognition_classes = paper_recognition_classes();
  // Recognition class -> the map class whose cells it lies on ("" = free space).
  // Every key must be in recognition_classes (checked when the options are read)
  // and every value a class the map declares (class_map_check.hpp, when the
  // localizer is built on its map).
  std::map<std::string, std::string> class_map{{"open_door", "door"},
                                               {"closed_door", "door"},
                                               {"open_glass_door", "glass_door"},
                                               {"closed_glass_door", "glass_door"},
                                               {"fence", "fence"},
                                               {"no_entry_line", "no_entry_line"},
                                               {"free_space", ""},
                                               {"others", "others"}};
  // Recognition class -> its frequency in the worlds the recognizer's rules
  // were fitted on (pi of recognition_model.hpp, divided out of the
  // recognizer's probabilities before Eq. (8)); printed by
  // slamer-calibrate-recognizer with the rules. Empty: none divided out. Else
  // it names every recognition class, with values in (0, 1].
  std::map<std::string, double> training_prior{
      {"open_door", 0.0464}, {"closed_door", 0.00864},  {"open_glass_door", 0.0184}, {"closed_glass_door", 0.0322},
      {"fence", 0.0279},     {"no_entry_line", 0.0019}, {"free_space", 0.273},       {"others", 0.591}};
  // pi is divided out raised to this power: 1 is Bayes' rule for a map prior
  // that is right, 0 divides nothing out; between, the map prior (which is
  // wrong where doors changed) does not get the whole of pi's role.
  double training_prior_exponent = 0.5;
  bool operator==(const SlamerOptions&) const = default;
};

// POSE.status. The evidence is the scan fit: the fraction of beams ending
// within fit_distance of an obstacle of the map at the estimate
// (scan_fit.hpp), smoothed over about 10 scans, and over fit_sustained_time.
struct StatusOptions {
  double uncertain_position_sigma = 0.5;   // [m] particles spread wider: UNCERTAIN
  double uncertain_ess_fraction = 0.05;    // ESS below this * particles: a few particles carry it all, UNCERTAIN
  double lost_mean_log_likelihood = -3.0;  // per used beam; below for `lost_after` scans: LOST
  int lost_after = 20;
  double fit_distance = 0.1;   // [m]
  double fit_expected = 0.9;   // typical fit at a correct pose: motion noise as configured at or above it
  double fit_uncertain = 0.5;  // smoothed fit below this: UNCERTAIN; the slow fit below it: search too
  double fit_lost = 0.3;       // below this for lost_after scans: LOST (until above fit_uncertain) and recovery
  // A global search (after LOST, or on demand) ends only when the smoothed fit
  // is this high: a wrong place of a building that looks alike fits about as
  // well as fit_uncertain, the right one about as well as fit_expected.
  double fit_confirm = 0.75;
  // The fit smoothed over fit_sustained_time below fit_sustained: UNCERTAIN. A
  // look-alike place fits well now and then, a correct pose nearly always.
  double fit_sustained = 0.65;
  double fit_sustained_time = 10.0;  // [s]
  // The estimate's travel along its heading summed against the odometry's over
  // the last odometry_disagreement_time and at most odometry_disagreement_distance
  // of driving, off by more than odometry_disagreement: UNCERTAIN
  // (odometry_agreement.hpp; 0: never). The distance: where 10 % of it, 5x the
  // worst uncalibrated wheel's scale error, reaches the bar.
  double odometry_disagreement = 0.5;           // [m]
  double odometry_disagreement_time = 10.0;     // [s]
  double odometry_disagreement_distance = 5.0;  // [m]
  // The scans scoring a pose along the estimate's heading (0.4-1.0 m ahead or
  // behind, along_track.hpp) better than the estimate by more than
  // along_track_gain per beam, scan after scan for along_track_time and
  // along_track_scans (two scans of a log with one every 3 s are not evidence):
  // UNCERTAIN (a slide along a corridor the fit cannot show; 0: never).
  double along_track_gain = 0.05;  // [log-likelihood per beam]
  double along_track_time = 2.0;   // [s]
  int along_track_scans = 10;
  // After the position along the heading was in doubt (a pose given or found
  // by search, a jump, a posterior on a handful of particles, the odometry
  // disagreement or the along-track rule above), UNCERTAIN until a scan fits
  // every pose 0.4-1.0 m along the heading worse than the estimate by
  // along_track_gain per beam (along_track.hpp). A corridor never pins it.
  bool along_track_pin = true;
  bool operator==(const StatusOptions&) const = default;
};

// Local scan matching (local_match.hpp) while tracking: when the scan fits
// the predicted pose worse than `below`, the pose within the window that
// explains the scan best is searched, and if it fits at least `gain` better
// than the best pose near the prediction, `fraction` of the particles (the
// least likely) are put around it. If the best other place in the window fits
// about as well (within `gain`), half of them go there when it too fits `gain`
// better than near the prediction, and none anywhere otherwise.
// The odometry's failures (a lost sign, a turn measured short) are then
// corrected from the scan before the cloud has left the right place.
struct LocalMatchOptions {
  double below = 0.75;    // scan fit at the prediction under this: search (0: never)
  double gain = 0.1;      // the match's fit must be this much higher to be used
  double fraction = 0.1;  // of the particles replaced around the match
  double shift = 0.5;     // [m] window in x and y
  double turn = 0.5;      // [rad] window in heading
  bool operator==(const LocalMatchOptions&) const = default;
};

// Relocalization while LOST or globally localizing, and local scan matching while tracking.
// Globally localizing, the best proposals replace `fraction` of the particles
// each scan. While LOST they form a cloud of their own of that size
// (particle_filter_challengers.cpp), and the tracked cloud moves to its place
// only once that place has fitted the scans at least status.fit_confirm and
// `adopt_margin` better than the tracked cloud for `adopt_time` (0: the
// proposals join the tracked cloud at once, as globally localizing).
struct RecoveryOptions {
  int candidates = 2000;      // poses scored against each scan
  double fraction = 0.1;      // of the particles
  double adopt_time = 2.0;    // [s]
  double adopt_margin = 0.1;  // scan fit
  // Probation after the cloud moved to the challengers' place: in a building
  // of look-alike places their first find may be the wrong one. For this long
  // the status is UNCERTAIN while the challengers search the rest of the map;
  // then it stays UNCERTAIN as long as they hold a rival (a place away from
  // the estimate that fits as a correct pose does and within adopt_margin as
  // well). The cloud is never moved on probation: the status only (0: none).
  double probation_time = 20.0;  // [s]
  // After a global localization, rival places keep particles of their own
  // (rival_places.hpp) until one leads the others by rival_margin nats of the
  // particle weights; the status is UNCERTAIN while more than one is left.
  // Not fitted (README, "Rival places"; Wean: 9 of 30 global localizations
  // home before, 19 with it).
  double rival_margin = 50.0;  // [nats] (0: ordinary resampling, no rivals kept)
  int rival_places = 8;        // the most kept
  // Meanwhile, each weighed scan this share of the search's proposals
  // (fraction of the particles) joins rival_margin behind the best place, so
  // a place the search missed becomes a rival by fitting better (0: none;
  // set once, not fitted; Wean: 29 of 45 runs home without, 35 with it).
  double late_proposals = 0.1;
  LocalMatchOptions local;
  bool operator==(const RecoveryOptions&) const = default;
};

// Resuming from the pose file after a restart (LocalizerNode::resume): the
// robot may have moved while the process was down.
struct ResumeOptions {
  double speed = 0.5;      // [m/s] the saved position's sigma grows by this x the downtime
  double turn_rate = 0.5;  // [rad/s] and its heading's (at most pi)
  double moved_fraction =
      0.5;  // of the particles so spread; the rest at the saved sigma (most restarts are on the spot)
  double max_downtime = 600.0;  // [s] down longer, or saved after the first scan: global localization
  int confirm_scans = 10;       // scans in a row that fit the map there before the status may say OK
  int confirm_within = 80;      // not confirmed within this many scans: global localization takes over
  bool operator==(const ResumeOptions&) const = default;
};

// Input streams (LocalizerNode).
struct InputOptions {
  double scan_timeout = 2.0;      // [s] no scan for this long: no pose, PROCESS_STATUS says so
  double objects_wait = 0.1;      // [s] how long a scan waits for its LINE_OBJECTS
  double odometry_wait = 0.05;    // [s] how long a scan waits for odometry past its time
  double objects_timeout = 1.0;   // [s] none for this long: the recognizer is missing, scans stop waiting
  double odometry_timeout = 0.5;  // [s] no odometry this close before a scan: odometry is missing
  bool operator==(const InputOptions&) const = default;
};

struct LocalizerOptions {
  LocalizerMode mode = LocalizerMode::kSlamer;
  int particles = 500;
  uint64_t seed = 1;
  double resample_threshold = 0.5;  // resample when ESS < this * particles (Sec. IV-F)
  Pose2 initial_pose;
  std::vector<double> initial_sigma{0.2, 0.2, 0.05};  // [m, m, rad]
  MotionOptions motion;
  LfmOptions lfm;
  SlfmOptions slfm;
  SlamerOptions slamer;
  StatusOptions status;
  RecoveryOptions recovery;
  ResumeOptions resume;
  InputOptions inputs;
};
void read_options(const ConfigReader& reader, LocalizerOptions* options);
LocalizerMode parse_mode(const std::string& text);  // throws std::invalid_argument

}  // namespace slamer

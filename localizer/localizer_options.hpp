// Options of the SLAMER localizer (a Rao-Blackwellized particle filter over
// the pose, with the objects' classes estimated analytically; paper Sec. IV)
// and its LFM / SLFM baselines.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/geometry/se2.hpp"
#include "common/map/likelihood_field.hpp"

namespace slamer {

class ConfigReader;  // common/config/config_reader.hpp: the YAML reader stays out of this header

enum class LocalizerMode { kLfm, kSlfm, kSlamer };

struct LocalizerOptions {
  LocalizerMode mode = LocalizerMode::kSlamer;
  int particles = 500;
  uint64_t seed = 1;
  // Motion noise (Eq. (5)): standard deviations of the odometry increment's
  // rotations and translation grow with the increment (Probabilistic Robotics 5.4).
  double alpha_rot_from_rot = 0.05;      // alpha1 [rad/rad]
  double alpha_rot_from_trans = 0.02;    // alpha2 [rad/m]
  double alpha_trans_from_trans = 0.05;  // alpha3 [m/m]
  double alpha_trans_from_rot = 0.02;    // alpha4 [m/rad]
  // Measurement model (LFM, Eqs. (10)-(13)).
  LikelihoodFieldOptions lfm;
  int beam_step = 1;          // use every n-th beam (1: all of them)
  double beam_weight = 0.05;  // exponent on each beam's likelihood: beams are not independent
  // SLFM (Eqs. (16)-(17)): each beam is weighed in the likelihood field of
  // the class of the object it hits. Eq. (17)'s exponential term for beams of
  // unknown class, lambda exp(-lambda r) / (1 - exp(-lambda r_max)), is the
  // same for every pose, so it cancels when the weights are normalized: such
  // beams are left out and lambda is no option.
  double slfm_support = 0.1;  // [m] a beam belongs to an object this close to it
  // SLAMER (Eqs. (7)-(9)).
  double dirichlet_a1 = 4.0;      // concentration of the true class
  double dirichlet_a2 = 1.0;      // of the others (a1 != a2, or the recognition model says nothing)
  double prior_sigma = 0.15;      // [m] sigma_d of the map prior
  double object_weight = 5.0;     // exponent on each object's term (tuned on paper_indoor)
  int object_samples = 3;         // points along an object for its representative distance
  double min_probability = 1e-3;  // recognizer probabilities are floored before log
  // Recognition class -> the map class whose cells it lies on ("" = free space).
  std::map<std::string, std::string> class_map{{"open_door", "door"},
                                               {"closed_door", "door"},
                                               {"open_glass_door", "glass_door"},
                                               {"closed_glass_door", "glass_door"},
                                               {"fence", "fence"},
                                               {"no_entry_line", "no_entry_line"},
                                               {"free_space", ""},
                                               {"others", "others"}};
  // Resampling (Sec. IV-F) and status.
  double resample_threshold = 0.5;  // resample when ESS < this * particles
  Pose2 initial_pose;
  std::vector<double> initial_sigma{0.2, 0.2, 0.1};  // [m, m, rad]
  double uncertain_position_sigma = 0.5;             // [m]
  double uncertain_ess_fraction = 0.05;    // ESS below this * particles: a few particles carry it all, UNCERTAIN
  double lost_mean_log_likelihood = -3.0;  // per used beam; below for `lost_after` scans: LOST
  int lost_after = 20;
  // Input streams (LocalizerNode).
  double scan_timeout = 2.0;           // [s] no scan for this long: no pose, PROCESS_STATUS says so
  double objects_wait = 0.1;           // [s] how long a scan waits for its LINE_OBJECTS
  double objects_timeout = 1.0;        // [s] none for this long: the recognizer is missing, scans stop waiting
  double odometry_timeout = 0.5;       // [s] no odometry this close before a scan: odometry is missing
  double no_odometry_speed = 0.5;      // [m/s] without odometry the particles diffuse this fast
  double no_odometry_turn_rate = 0.5;  // [rad/s]
};
void read_options(const ConfigReader& reader, LocalizerOptions* options);
LocalizerMode parse_mode(const std::string& text);  // throws std::invalid_argument

}  // namespace slamer

// Fitting the recognizer to simulated runs (slamer-calibrate-recognizer).
//
// Class rules: every recognized object goes in a feature bin (kind, coverage
// and length for physical lines; length for spatial ones) and is labelled with
// the true world's class where the ground-truth pose puts it; a bin's rule gets
// the class frequencies seen in it plus a pseudo-count, which makes the
// recognizer's most likely class the most often right one, and its
// probabilities calibrated on the worlds it was fitted on.
//
// Recognition model (paper Eq. (8)): SLAMER's class posterior is proportional
// to Dir(c; a) x map prior, and over the classes Dir(c; a) only varies as
// c_l^(a1 - a2). So a1 - a2 is a temperature on the recognizer's confidence:
// fitted by maximum likelihood of the true classes under c_l^t / sum_k c_k^t on
// objects of worlds the rules were NOT fitted on (two folds), it says how far
// the recognizer's confidence carries to a building it has not seen. The
// paper sets a1 and a2 "respecting the performance of the recognition method";
// this measures it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "recognizer/recognizer_config.hpp"
#include "tools/eval/eval_config.hpp"

namespace slamer {

struct LabelledObject {
  int bin = -1;               // index into bin_rules()
  int truth = -1;             // index into the recognizer's classes
  bool right_before = false;  // the given rules' most likely class was the truth
};

// The rule grid: one rule per bin, no probabilities yet.
std::vector<ClassRule> bin_rules();

// The objects the recognizer (with `config`'s options) finds in simulated logs
// (LIDAR + GROUND_TRUTH) of `world_file`, labelled with their true class;
// objects whose truth is not one of the recognizer's classes are left out.
// Problems reading a log are appended to `problems`.
std::vector<LabelledObject> labelled_objects(const std::string& world_file, const std::vector<std::string>& logs,
                                             const RecognizerProcessConfig& config, const EvalConfig& eval,
                                             std::string* problems);

struct FittedRules {
  std::vector<ClassRule> rules;            // the bins that had objects, with probabilities
  std::vector<int64_t> objects;            // per rule
  std::vector<std::vector<double>> probs;  // per bin of bin_rules() (normalized), empty where no objects
  int64_t right = 0;                       // objects whose bin's most likely class is theirs
  // Per class: its share of the objects under the rules (sum over bins of the
  // bin's objects x its probability, over all objects), the training prior pi
  // that localizer.slamer.training_prior divides out.
  std::vector<double> class_prior;
};
FittedRules fit_rules(const std::vector<LabelledObject>& objects, const std::vector<std::string>& classes,
                      double prior);

// Objects scored with rules fitted without them.
struct HeldOut {
  const FittedRules* rules = nullptr;
  const std::vector<LabelledObject>* objects = nullptr;
};
// The temperature t maximizing sum log(pi_truth q_truth^t / sum_k pi_k q_k^t)
// over the held-out objects: q their bins' probabilities with the rules' class
// prior pi divided out (recognition_model.hpp's divide_out_prior), which is
// how the localizer uses them with the map prior in pi's place. Bins the rules
// never saw are left out. Searched on [0.05, 6].
double fit_temperature(const std::vector<HeldOut>& folds, double min_probability);

// The rules as YAML lines for config/recognizer.yaml's `rules:`.
std::string rules_yaml(const FittedRules& fitted, const std::vector<std::string>& classes);

// The class prior as config/localizer.yaml's `training_prior:` lines.
std::string training_prior_yaml(const FittedRules& fitted, const std::vector<std::string>& classes);

}  // namespace slamer

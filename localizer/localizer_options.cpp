#include "localizer/localizer_options.hpp"

#include "common/config/config_reader.hpp"

#include <algorithm>
#include <initializer_list>
#include <stdexcept>
#include <string_view>

#include "common/robot/robot_options.hpp"
#include "localizer/class_map_check.hpp"

namespace slamer {

LocalizerMode parse_mode(const std::string& text) {
  if (text == "lfm") {
    return LocalizerMode::kLfm;
  }
  if (text == "slfm") {
    return LocalizerMode::kSlfm;
  }
  if (text == "slamer") {
    return LocalizerMode::kSlamer;
  }
  throw std::invalid_argument("mode must be lfm, slfm or slamer, got '" + text + "'");
}

namespace {

// An enum read as one of `names`, given in the enum's order.
template <typename Enum>
void read_enum(const ConfigReader& reader, std::string_view key, Enum* value,
               std::initializer_list<std::string_view> names) {
  std::string choice(names.begin()[static_cast<std::size_t>(*value)]);
  reader.read_choice(key, &choice, names);
  *value = static_cast<Enum>(std::find(names.begin(), names.end(), choice) - names.begin());
}

}  // namespace

void read_options(const ConfigReader& reader, MotionOptions* o) {
  reader.read("alpha_rot_from_rot", &o->alpha_rot_from_rot, non_negative());
  reader.read("alpha_rot_from_trans", &o->alpha_rot_from_trans, non_negative());
  reader.read("alpha_trans_from_trans", &o->alpha_trans_from_trans, non_negative());
  reader.read("alpha_trans_from_rot", &o->alpha_trans_from_rot, non_negative());
  reader.read("noise_gain_max", &o->noise_gain_max, in_range(1.0, 100.0));
  reader.read("noise_floor_trans", &o->noise_floor_trans, in_range(0.0, 1.0));
  reader.read("noise_floor_rot", &o->noise_floor_rot, in_range(0.0, 1.0));
  reader.read("noise_floor_interval", &o->noise_floor_interval, in_range(1e-3, 100.0));
  reader.read("heading_slip_fraction", &o->heading_slip_fraction, probability());
  reader.read("heading_slip_sigma", &o->heading_slip_sigma, in_range(0.0, 1.0));
  reader.read("odometry_correction_memory", &o->odometry_correction_memory, in_range(0.0, 1000.0));
  reader.read("no_odometry_speed", &o->no_odometry_speed, in_range(0.0, 10.0));
  reader.read("no_odometry_turn_rate", &o->no_odometry_turn_rate, in_range(0.0, 10.0));
}

void read_options(const ConfigReader& reader, LfmOptions* o) {
  reader.read("sigma_hit", &o->sigma_hit, positive());
  reader.read("z_hit", &o->z_hit, probability());
  reader.read("z_max", &o->z_max, probability());
  reader.read("z_rand", &o->z_rand, probability());
  reader.read("range_max", &o->range_max, positive());
  if (std::abs(o->z_hit + o->z_max + o->z_rand - 1.0) > 1e-6) {
    reader.fail("z_rand", "z_hit + z_max + z_rand must be 1");
  }
  if (!(o->z_rand > 0.0)) {
    reader.fail("z_rand", "must be > 0: a beam off the map would have probability 0");
  }
  reader.read("beam_step", &o->beam_step, in_range(1, 10000));
  reader.read("beam_weight", &o->beam_weight, in_range(1e-6, 1.0));
}

void read_options(const ConfigReader& reader, SlfmOptions* o) {
  reader.read("support", &o->support, positive());
}

void read_options(const ConfigReader& reader, SlamerOptions* o) {
  reader.read("dirichlet_a1", &o->dirichlet_a1, positive());
  reader.read("dirichlet_a2", &o->dirichlet_a2, positive());
  reader.read("prior_sigma", &o->prior_sigma, positive());
  reader.read("free_space_margin", &o->free_space_margin, in_range(0.0, 2.0));
  if (reader.has("free_space_class_margins")) {
    const ConfigReader margins = reader.section("free_space_class_margins");
    o->free_space_class_margins.clear();
    for (const std::string& name : margins.keys()) {
      margins.read(name, &o->free_space_class_margins[name], in_range(0.01, 2.0));
    }
  }
  read_enum(reader, "spatial_line_ends", &o->spatial_line_ends, {"scored", "left_out_for_free_space", "left_out"});
  read_enum(reader, "physical_line_distance", &o->physical_line_distance, {"mean", "farthest"});
  reader.read("unmapped_probability", &o->unmapped_probability, in_range(0.0, 0.99));
  reader.read("posterior_unmapped_probability", &o->posterior_unmapped_probability, in_range(0.0, 0.99));
  reader.read("object_weight", &o->object_weight, in_range(0.0, 10.0));
  reader.read("object_samples", &o->object_samples, in_range(1, 50));
  reader.read("min_probability", &o->min_probability, in_range(1e-12, 0.1));
  reader.read("recognition_classes", &o->recognition_classes);
  if (o->recognition_classes.empty()) {
    reader.fail("recognition_classes", "the list is empty");
  }
  if (reader.has("class_map")) {
    const ConfigReader classes = reader.section("class_map");
    o->class_map.clear();
    for (const std::string& name : classes.keys()) {
      std::string map_class;
      classes.read(name, &map_class);
      o->class_map[name] = map_class;
    }
  }
  // Every entry names a class the recognizer emits (the default table too, against a configured list).
  for (const auto& entry : o->class_map) {
    if (const std::string problem = recognition_class_problem(*o, entry.first); !problem.empty()) {
      if (reader.section("class_map").has(entry.first)) {
        reader.section("class_map").fail(entry.first, problem);
      }
      reader.fail("recognition_classes", "class_map's " + problem);
    }
  }
  if (reader.has("training_prior")) {
    const ConfigReader prior = reader.section("training_prior");
    o->training_prior.clear();
    for (const std::string& name : prior.keys()) {
      double p = 0.0;
      prior.read(name, &p, in_range(1e-9, 1.0));
      if (const std::string problem = recognition_class_problem(*o, name); !problem.empty()) {
        prior.fail(name, problem);
      }
      o->training_prior[name] = p;
    }
  }
  reader.read("training_prior_exponent", &o->training_prior_exponent, in_range(0.0, 1.0));
  for (const std::string& name : o->recognition_classes) {
    if (!o->training_prior.empty() && o->training_prior.count(name) == 0) {
      reader.fail("training_prior",
                  "lacks the recognition class '" + name + "' (name every one, or write {} to divide nothing out)");
    }
  }
}

void read_options(const ConfigReader& reader, StatusOptions* o) {
  reader.read("uncertain_position_sigma", &o->uncertain_position_sigma, positive());
  reader.read("uncertain_ess_fraction", &o->uncertain_ess_fraction, probability());
  reader.read("lost_mean_log_likelihood", &o->lost_mean_log_likelihood);
  reader.read("lost_after", &o->lost_after, at_least(1));
  reader.read("fit_distance", &o->fit_distance, in_range(0.01, 1.0));
  reader.read("fit_expected", &o->fit_expected, probability());
  reader.read("fit_uncertain", &o->fit_uncertain, probability());
  reader.read("fit_lost", &o->fit_lost, probability());
  reader.read("fit_confirm", &o->fit_confirm, probability());
  reader.read("fit_sustained", &o->fit_sustained, probability());
  reader.read("fit_sustained_time", &o->fit_sustained_time, in_range(0.1, 600.0));
  reader.read("odometry_disagreement", &o->odometry_disagreement, non_negative());
  reader.read("odometry_disagreement_time", &o->odometry_disagreement_time, in_range(0.1, 600.0));
  reader.read("odometry_disagreement_distance", &o->odometry_disagreement_distance, positive());
  reader.read("along_track_gain", &o->along_track_gain, non_negative());
  reader.read("along_track_time", &o->along_track_time, in_range(0.0, 600.0));
  reader.read("along_track_scans", &o->along_track_scans, at_least(1));
  reader.read("along_track_pin", &o->along_track_pin);
  if (!(o->fit_lost <= o->fit_uncertain && o->fit_uncertain < o->fit_expected)) {
    reader.fail("fit_uncertain", "needs fit_lost <= fit_uncertain < fit_expected");
  }
  if (!(o->fit_uncertain <= o->fit_confirm && o->fit_confirm <= o->fit_expected)) {
    reader.fail("fit_confirm", "needs fit_uncertain <= fit_confirm <= fit_expected");
  }
  if (!(o->fit_uncertain <= o->fit_sustained && o->fit_sustained <= o->fit_expected)) {
    reader.fail("fit_sustained", "needs fit_uncertain <= fit_sustained <= fit_expected");
  }
}

void read_options(const ConfigReader& reader, LocalMatchOptions* o) {
  reader.read("below", &o->below, probability());
  reader.read("gain", &o->gain, probability());
  reader.read("fraction", &o->fraction, probability());
  reader.read("shift", &o->shift, in_range(0.0, 5.0));
  reader.read("turn", &o->turn, in_range(0.0, 3.2));
}

void read_options(const ConfigReader& reader, RecoveryOptions* o) {
  reader.read("candidates", &o->candidates, in_range(0, 1'000'000));
  reader.read("fraction", &o->fraction, probability());
  reader.read("adopt_time", &o->adopt_time, in_range(0.0, 60.0));
  reader.read("adopt_margin", &o->adopt_margin, probability());
  reader.read("probation_time", &o->probation_time, in_range(0.0, 600.0));
  reader.read("rival_margin", &o->rival_margin, in_range(0.0, 1e6));
  reader.read("rival_places", &o->rival_places, in_range(1, 64));
  reader.read("late_proposals", &o->late_proposals, in_range(0.0, 1.0));
  read_options(reader.section("local"), &o->local);
}

void read_options(const ConfigReader& reader, ResumeOptions* o) {
  reader.read("speed", &o->speed, non_negative());
  reader.read("turn_rate", &o->turn_rate, non_negative());
  reader.read("moved_fraction", &o->moved_fraction, probability());
  reader.read("max_downtime", &o->max_downtime, non_negative());
  reader.read("confirm_scans", &o->confirm_scans, in_range(1, 100000));
  reader.read("confirm_within", &o->confirm_within, in_range(1, 100000));
  if (o->confirm_within < o->confirm_scans) {
    reader.fail("confirm_within", "must be at least confirm_scans");
  }
}

void read_options(const ConfigReader& reader, InputOptions* o) {
  reader.read("scan_timeout", &o->scan_timeout, in_range(0.01, 60.0));
  reader.read("objects_wait", &o->objects_wait, in_range(0.0, 10.0));
  reader.read("odometry_wait", &o->odometry_wait, in_range(0.0, 10.0));
  reader.read("objects_timeout", &o->objects_timeout, in_range(0.01, 60.0));
  reader.read("odometry_timeout", &o->odometry_timeout, in_range(0.01, 60.0));
}

void read_options(const ConfigReader& reader, LocalizerOptions* o) {
  std::string mode = o->mode == LocalizerMode::kLfm ? "lfm" : o->mode == LocalizerMode::kSlfm ? "slfm" : "slamer";
  reader.read_choice("mode", &mode, {"lfm", "slfm", "slamer"});
  o->mode = parse_mode(mode);
  reader.read("particles", &o->particles, in_range(1, 1'000'000));
  int64_t seed = static_cast<int64_t>(o->seed);
  reader.read("seed", &seed, non_negative());
  o->seed = static_cast<uint64_t>(seed);
  reader.read("resample_threshold", &o->resample_threshold, probability());
  o->initial_pose = read_pose(reader, "initial_pose", o->initial_pose);
  reader.read("initial_sigma", &o->initial_sigma, non_negative(), 3);
  read_options(reader.section("motion"), &o->motion);
  read_options(reader.section("lfm"), &o->lfm);
  read_options(reader.section("slfm"), &o->slfm);
  read_options(reader.section("slamer"), &o->slamer);
  read_options(reader.section("status"), &o->status);
  read_options(reader.section("recovery"), &o->recovery);
  read_options(reader.section("resume"), &o->resume);
  read_options(reader.section("inputs"), &o->inputs);
}

}  // namespace slamer

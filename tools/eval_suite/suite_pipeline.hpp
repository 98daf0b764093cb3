// One test world of slamer-eval-suite through the offline pipeline, with the
// stack's own programs: slamer-gen-world, slamer-sim (realistic odometry from
// the sim config), slamer-recognizer --replay, slamer-localizer --replay in
// lfm, slfm and slamer modes from the world's start, then scored with the
// slamer-eval library against the world's truth and its map.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tools/eval/eval_config.hpp"
#include "tools/eval_suite/suite_report.hpp"

namespace slamer {

struct SuiteSetup {
  std::string bin_dir;  // where the programs are
  std::string sim_config, recognizer_config, localizer_config;
  std::string gen_config;   // "" = the generator's defaults
  int jobs = 2;             // localizer runs at once
  int localizer_seeds = 1;  // each mode runs with localizer seeds 1..this
  bool keep_logs = false;
  bool reuse_logs = false;  // score the logs a kept earlier run left instead of running again
};

// slamer-gen-world and slamer-sim (the sim config, sim seed = world seed) for
// world `seed` into `directory`: world/world.yaml and sim.lcm, returned in this
// order. sim.lcm appears only once complete. Throws std::runtime_error naming
// the step that failed.
std::pair<std::string, std::string> simulate_world(const SuiteSetup& setup, uint64_t seed,
                                                   const std::string& directory);

// The log of a localizer run: MODE.lcm for localizer seed 1, MODE-sS.lcm for seed S.
std::string localizer_log(const std::string& mode, int localizer_seed);

// Runs everything in `directory`, one result per localizer seed (1..setup.localizer_seeds);
// throws std::runtime_error naming the step that failed.
std::vector<WorldResult> run_world(const SuiteSetup& setup, const EvalConfig& eval, uint64_t seed,
                                   const std::string& directory);

}  // namespace slamer

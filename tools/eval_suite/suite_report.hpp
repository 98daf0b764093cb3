// What slamer-eval-suite prints over generated test worlds (issue 11): the
// paper's table per world (LFM, SLFM, SLAMER runs side by side), one line per
// world and the aggregate (mean, and worst: the largest error, the lowest
// accuracy), the per-class confusion matrices of the recognizer, the map-based
// method and SLAMER summed over the worlds, the shares of their objects
// labelled a door or no_entry_line where there is none, and the map-differs
// cases apart (objects whose true class differs from the map's; the doors that do).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/eval/report.hpp"
#include "tools/eval_suite/door_scores.hpp"
#include "tools/worldgen/world_files.hpp"

namespace slamer {

// Seeds: training worlds (calibration) use 1..99999; test world k (k < 1000)
// of a suite run with seed S is 100000 + 1000 * S + k, so they never meet.
constexpr uint64_t kTrainingSeedsEnd = 100000;
uint64_t test_world_seed(uint64_t suite_seed, int index);

// One world with one localizer seed.
struct WorldResult {
  uint64_t seed = 0;
  int localizer_seed = 1;
  MapDifferences differences;
  std::vector<NamedRun> runs;  // lfm, slfm, slamer in this order
  DoorScores doors;            // the doors in another state than the map, in the SLAMER run
  DoorScores changing_doors;   // the doors that change during the run
};

std::string render_world(const WorldResult& world, const EvalOptions& options);
// Over every run of `worlds` (a world once per localizer seed): the goals'
// counts ("on N of M worlds") take each world's mean over its localizer seeds.
std::string render_summary(const std::vector<WorldResult>& worlds, const EvalOptions& options);

}  // namespace slamer

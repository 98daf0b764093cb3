// The doors whose truth differs from the map (issue 11's goal: SLAMER gets
// such a door's state right in 80 % of the scans that see it within 5 m):
// every recognized object whose middle lies on such a door (within half its
// width + 0.3 m of its centre, at the true pose) in a scan taken within
// `range` of it, scored for the recognizer, the map-based method and SLAMER
// against the door's true class at that time. `changing` picks the doors that
// change during the run (from their first change on, when they differ from
// the map), else those in another state than the map throughout.
#pragma once

#include "tools/eval/evaluation.hpp"
#include "tools/worldgen/world_files.hpp"

namespace slamer {

struct DoorScores {
  int64_t objects = 0;
  int64_t recognizer = 0, map_based = 0, slamer = 0;  // right
  int64_t doors_seen = 0;                             // differing doors with at least one object
  void merge(const DoorScores& other);
};

DoorScores score_differing_doors(const RunInputs& run, const TrueWorld& truth_world, const TrueWorld& map_world,
                                 const Pose2& lidar_mount, const EvalOptions& options,
                                 const MapDifferences& differences, bool changing, double range = 5.0);

}  // namespace slamer

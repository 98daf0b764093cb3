// When a localizer's estimate settles, for logs without a reference (the CMU
// Wean logs start at an unknown pose and have no ground truth; issue 9 asks
// after how many scans and seconds global localization settles): the first
// scan from which no pose jumps more than `max_jump` from the one before and
// at least `ok_fraction` of the poses say OK, that scan included. A settled
// estimate is not thereby a right one: a look-alike place settles too, so runs
// with other seeds or particle counts that end elsewhere say which is wrong.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "tools/datasets/bench_scoring.hpp"

namespace slamer {

struct Settling {
  int64_t scans = 0;
  std::optional<int64_t> scan;  // the first scan of the settled stretch (0-based); none: never
  double seconds = 0.0;         // from the first pose to it
  double ok_fraction = 0.0;     // of all the poses
  Pose2 end;                    // the last pose
};

Settling settling(const std::vector<PoseReport>& poses, double max_jump = 0.5, double ok_fraction = 0.9);

}  // namespace slamer

// When a localizer's estimate settles, for logs without a reference (the CMU
// Wean logs start at an unknown pose and have no ground truth; issue 9 asks
// after how many scans and seconds global localization settles): the first
// scan from which no pose jumps more than `max_jump` from the one before and
// at least `ok_fraction` of the poses say OK, that scan included. A settled
// estimate is not thereby a right one: a look-alike place settles too, so runs
// with other seeds or particle counts that end elsewhere say which is wrong.
// Hence the second measure: from which scan independent runs of one log (other
// seeds) agree, every pose of every run within `within` of the others' to the end.
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

struct Agreement {
  int64_t scans = 0;            // scans every run has a pose for (matched by utime)
  std::optional<int64_t> scan;  // the first of them from which the runs agree to the end; none: never
  double seconds = 0.0;         // from the first of them to it
  double spread_after = 0.0;    // the largest distance between two runs' poses from `scan` on [m]
  double spread_at_end = 0.0;   // at the last scan [m]
};

// Needs two runs or more (std::invalid_argument otherwise).
Agreement agreement(const std::vector<std::vector<PoseReport>>& runs, double within = 0.5);

// Where not every run agrees: which do. Two runs are linked when they agree
// within `within` to the end; a group is linked runs (transitively), each
// with the agreement of its runs together (which may be never, if a chain of
// links spans more than `within`). Groups in the order of their first run,
// runs by index into `runs`; a run that agrees with none is a group alone.
struct AgreeingGroup {
  std::vector<std::size_t> runs;
  Agreement agreement;  // of these runs together; default for a run alone
};
std::vector<AgreeingGroup> agreeing_groups(const std::vector<std::vector<PoseReport>>& runs, double within = 0.5);

}  // namespace slamer

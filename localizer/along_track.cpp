#include "localizer/along_track.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slamer {

AlongTrackPreference along_track_preference(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                                            const Pose2& base, const AlongTrackShifts& shifts) {
  if (points.x.empty() || !(shifts.step > 0.0)) {
    return {};
  }
  const std::size_t step =
      std::max<std::size_t>(1, points.x.size() / static_cast<std::size_t>(std::max(shifts.beams, 1)));
  const ScanPoints thinned = thinned_points(points, step);
  const std::size_t used = thinned.x.size();
  const auto score = [&](const Pose2& pose) {
    return field_log_likelihood(field, thinned, sensor_in_cells(field.geometry(), pose, mount));
  };
  const double at_base = score(base);
  double best_shifted = -std::numeric_limits<double>::infinity();
  double best_shift = 0.0;
  const double c = std::cos(base.theta);
  const double s = std::sin(base.theta);
  const int count = static_cast<int>(std::floor((shifts.farthest - shifts.nearest) / shifts.step + 1e-9));
  for (int k = 0; k <= count; ++k) {
    for (const double sign : {-1.0, 1.0}) {
      const double d = sign * (shifts.nearest + k * shifts.step);
      const double v = score({base.x + d * c, base.y + d * s, base.theta});
      if (v > best_shifted) {
        best_shifted = v;
        best_shift = d;
      }
    }
  }
  AlongTrackPreference best;
  best.margin = (at_base - best_shifted) / static_cast<double>(used);
  if (best.margin < 0.0) {
    best.shift = best_shift;
    best.gain = -best.margin;
  }
  return best;
}

}  // namespace slamer

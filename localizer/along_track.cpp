#include "localizer/along_track.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

AlongTrackPreference along_track_preference(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                                            const Pose2& base, const AlongTrackShifts& shifts) {
  if (points.x.empty() || !(shifts.step > 0.0)) {
    return {};
  }
  const std::size_t step =
      std::max<std::size_t>(1, points.x.size() / static_cast<std::size_t>(std::max(shifts.beams, 1)));
  const std::size_t used = (points.x.size() + step - 1) / step;
  const auto score = [&](const Pose2& pose) {
    return field_log_likelihood(field, points, sensor_in_cells(field.geometry(), pose, mount), step);
  };
  const double at_base = score(base);
  AlongTrackPreference best;
  double best_score = at_base;
  const double c = std::cos(base.theta);
  const double s = std::sin(base.theta);
  const int count = static_cast<int>(std::floor((shifts.farthest - shifts.nearest) / shifts.step + 1e-9));
  for (int k = 0; k <= count; ++k) {
    for (const double sign : {-1.0, 1.0}) {
      const double d = sign * (shifts.nearest + k * shifts.step);
      const double v = score({base.x + d * c, base.y + d * s, base.theta});
      if (v > best_score) {
        best_score = v;
        best.shift = d;
      }
    }
  }
  best.gain = (best_score - at_base) / static_cast<double>(used);
  return best;
}

}  // namespace slamer

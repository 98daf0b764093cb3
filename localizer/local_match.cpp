#include "localizer/local_match.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace slamer {

namespace {

struct Scored {
  Pose2 sensor;  // cells, rad
  double score;
};

// Coordinate ascent from `from` below the grid's resolution, steps halving
// three times, never leaving the window around `start`.
Scored refine(const LikelihoodField& field, const ScanPoints& points, const Pose2& start, double shift_cells,
              double turn, double step_cells, double turn_step, Scored from) {
  double dxy = step_cells / 2.0;
  double dtheta = turn_step / 2.0;
  for (int level = 0; level < 3; ++level, dxy /= 2.0, dtheta /= 2.0) {
    for (int moves = 0; moves < 8; ++moves) {
      const Pose2& b = from.sensor;
      const Pose2 tries[6] = {{b.x + dxy, b.y, b.theta}, {b.x - dxy, b.y, b.theta},    {b.x, b.y + dxy, b.theta},
                              {b.x, b.y - dxy, b.theta}, {b.x, b.y, b.theta + dtheta}, {b.x, b.y, b.theta - dtheta}};
      const Scored before = from;
      for (const Pose2& t : tries) {
        if (std::abs(t.x - start.x) > shift_cells || std::abs(t.y - start.y) > shift_cells ||
            std::abs(t.theta - start.theta) > turn) {
          continue;  // the window bounds the refinement too
        }
        const double s = field_log_likelihood(field, points, t);
        if (s > from.score) {
          from = {t, s};
        }
      }
      if (from.score == before.score) {
        break;
      }
    }
  }
  return from;
}

// Back from the sensor in cells (sensor_in_cells) to the base in the map frame.
Pose2 base_in_map(const GridGeometry& g, const Pose2& sensor, const Pose2& mount) {
  return compose(compose(g.origin, {sensor.x * g.resolution, sensor.y * g.resolution, wrap_angle(sensor.theta)}),
                 inverse(mount));
}

}  // namespace

LocalMatch match_locally(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount,
                         const Pose2& predicted, const LocalMatchWindow& window) {
  if (points.x.empty()) {
    return {predicted, 0.0, predicted};
  }
  const GridGeometry& g = field.geometry();
  const std::size_t step =
      std::max<std::size_t>(1, points.x.size() / static_cast<std::size_t>(std::max(window.beams, 1)));
  const Pose2 start = sensor_in_cells(g, predicted, mount);  // cells, rad
  const double shift_cells = window.shift / g.resolution;
  // The grid's translations are whole cells (the nearest number of them to
  // the step, at least one), so each heading's points are placed once and
  // only moved: the refinement below works under a cell.
  const int step_cells = std::max(1, static_cast<int>(std::lround(std::min(window.shift_step / g.resolution, 1e6))));
  const double turn_step = std::max(window.turn_step, 1e-4);
  const int shifts = static_cast<int>(std::floor(shift_cells / step_cells + 1e-9));
  const int turns = static_cast<int>(std::floor(window.turn / turn_step + 1e-9));

  // Every pose of the grid, indexed (heading, row, column).
  const int side = 2 * shifts + 1;
  const auto index = [&](int k, int iy, int ix) { return ((k + turns) * side + (iy + shifts)) * side + ix + shifts; };
  std::vector<Scored> grid(static_cast<std::size_t>((2 * turns + 1) * side * side));
  const ScanPoints thinned = thinned_points(points, step);
  for (int k = -turns; k <= turns; ++k) {
    const double theta = start.theta + k * turn_step;
    const LikelihoodField::CellScan placed = field.place_cells(
        thinned.x.data(), thinned.y.data(), thinned.x.size(), static_cast<float>(std::cos(theta)),
        static_cast<float>(std::sin(theta)), static_cast<float>(start.x), static_cast<float>(start.y));
    for (int iy = -shifts; iy <= shifts; ++iy) {
      for (int ix = -shifts; ix <= shifts; ++ix) {
        grid[static_cast<std::size_t>(index(k, iy, ix))] = {
            {start.x + ix * step_cells, start.y + iy * step_cells, theta},
            field.sum_shifted(placed, ix * step_cells, iy * step_cells)};
      }
    }
  }
  // The best pose (the prediction, the grid's centre, wins ties), and the best
  // local maximum of the grid apart from it: another place the scan fits, not
  // the best one's shoulder.
  const auto at = [&](int k, int iy, int ix) -> const Scored& {
    return grid[static_cast<std::size_t>(index(k, iy, ix))];
  };
  Scored best = at(0, 0, 0);
  for (const Scored& c : grid) {
    best = c.score > best.score ? c : best;
  }
  const auto peak = [&](int k, int iy, int ix) {
    const double s = at(k, iy, ix).score;
    return (k == -turns || at(k - 1, iy, ix).score <= s) && (k == turns || at(k + 1, iy, ix).score <= s) &&
           (iy == -shifts || at(k, iy - 1, ix).score <= s) && (iy == shifts || at(k, iy + 1, ix).score <= s) &&
           (ix == -shifts || at(k, iy, ix - 1).score <= s) && (ix == shifts || at(k, iy, ix + 1).score <= s);
  };
  const double apart_cells = window.separation / g.resolution;
  const auto apart = [&](const Scored& c) {
    return std::hypot(c.sensor.x - best.sensor.x, c.sensor.y - best.sensor.y) > apart_cells ||
           std::abs(c.sensor.theta - best.sensor.theta) > window.separation_turn;
  };
  std::optional<Scored> other;
  for (int k = -turns; k <= turns; ++k) {
    for (int iy = -shifts; iy <= shifts; ++iy) {
      for (int ix = -shifts; ix <= shifts; ++ix) {
        const Scored& c = at(k, iy, ix);
        // The score first: most poses score below the runner-up so far.
        if ((!other || c.score > other->score) && apart(c) && peak(k, iy, ix)) {
          other = c;
        }
      }
    }
  }

  const auto refined = [&](const Scored& from) {
    return refine(field, thinned, start, shift_cells, window.turn, step_cells, turn_step, from);
  };
  const Scored matched = refined(best);
  const std::size_t used = (points.x.size() + step - 1) / step;
  return {base_in_map(g, matched.sensor, mount), matched.score / static_cast<double>(used),
          base_in_map(g, refined(other.value_or(best)).sensor, mount)};
}

Pose2 climb_locally(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount, const Pose2& start,
                    double shift, double turn, int beams) {
  if (points.x.empty()) {
    return start;
  }
  const GridGeometry& g = field.geometry();
  const std::size_t step = std::max<std::size_t>(1, points.x.size() / static_cast<std::size_t>(std::max(beams, 1)));
  const Pose2 sensor = sensor_in_cells(g, start, mount);
  const double step_cells = 2.0 * shift / g.resolution;  // refine() starts at half the grid's step
  const ScanPoints thinned = thinned_points(points, step);
  const Scored from{sensor, field_log_likelihood(field, thinned, sensor)};
  const Scored climbed = refine(field, thinned, sensor, 2.0 * step_cells, 4.0 * turn, step_cells, 2.0 * turn, from);
  return base_in_map(g, climbed.sensor, mount);
}

}  // namespace slamer

#include "tools/worldgen/world_check.hpp"

#include <cmath>
#include <deque>
#include <set>
#include <sstream>

#include "tools/sim/world.hpp"

namespace slamer {
namespace {

std::string where(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out.precision(2);
  out << std::fixed << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

// Flood fill over cells the map shows free (doors shut) from the seeds.
void check_closed(const SemanticMap& map, const std::vector<std::string>& door_classes,
                  const std::vector<Eigen::Vector2d>& seeds, WorldCheckResult* result) {
  const GridGeometry& g = map.geometry;
  std::vector<bool> door_class(map.classes.size(), false);
  for (std::size_t c = 0; c < map.classes.size(); ++c) {
    for (const std::string& name : door_classes) {
      door_class[c] = door_class[c] || map.classes[c].name == name;
    }
  }
  std::vector<uint8_t> seen(g.size(), 0);
  std::deque<Cell> queue;
  for (const Eigen::Vector2d& seed : seeds) {
    if (const std::optional<Cell> cell = g.cell_at(seed); cell && !seen[g.index(cell->x, cell->y)]) {
      seen[g.index(cell->x, cell->y)] = 1;
      queue.push_back(*cell);
    }
  }
  while (!queue.empty()) {
    const Cell c = queue.front();
    queue.pop_front();
    const std::size_t i = g.index(c.x, c.y);
    ++result->reachable_cells;
    if (map.occupancy[i] == Occupancy::kUnknown || c.x == 0 || c.y == 0 || c.x == g.width - 1 || c.y == g.height - 1) {
      result->problems.push_back("a region the route reaches is open to the outside at " +
                                 where(g.cell_center(c.x, c.y)));
      return;
    }
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = c.x + dx;
      const int ny = c.y + dy;
      if (!g.contains(nx, ny) || seen[g.index(nx, ny)]) {
        continue;
      }
      const std::size_t n = g.index(nx, ny);
      const int label = map.labels[n];
      if (map.occupancy[n] == Occupancy::kOccupied || (label >= 0 && door_class[static_cast<std::size_t>(label)])) {
        continue;
      }
      seen[n] = 1;
      queue.push_back({nx, ny});
    }
  }
}

}  // namespace

WorldCheckResult check_world(const std::string& world_file, double clearance) {
  WorldCheckResult result;
  const auto options = load_options<WorldOptions>(world_file);
  const TrueWorld truth(load_semantic_map(options.map_path), options, world_file);
  std::vector<Eigen::Vector2d> route{{options.start.x, options.start.y}};
  for (const PathStep& step : options.path) {
    if (step.kind == PathStep::Kind::kGoTo) {
      route.push_back(step.target);
    }
  }
  check_closed(truth.map(), options.door_classes, route, &result);

  std::set<double> times{0.0};
  for (const DoorTruth& door : options.doors) {
    for (const auto& change : door.changes) {
      times.insert(change.first);
    }
  }
  const double step = 0.02;
  for (std::size_t leg = 0; leg + 1 < route.size(); ++leg) {
    const Eigen::Vector2d a = route[leg];
    const Eigen::Vector2d b = route[leg + 1];
    const double length = (b - a).norm();
    result.route_length += length;
    const Eigen::Vector2d along = length > 0.0 ? Eigen::Vector2d((b - a) / length) : Eigen::Vector2d(1.0, 0.0);
    const Eigen::Vector2d side(-along.y(), along.x());
    bool reported = false;
    for (double s = 0.0; s <= length && !reported; s += step) {
      for (double u = -clearance; u <= clearance + 1e-9 && !reported; u += 0.05) {
        const Eigen::Vector2d p = a + s * along + u * side;
        int door = -1;
        const int label = truth.class_near(p, 0.05, &door);
        if (label < 0) {
          continue;
        }
        bool open = door >= 0;
        for (const double t : times) {
          open = open && truth.door_state(door, t) == DoorState::kOpen;
        }
        if (!open) {
          result.problems.push_back("route leg " + std::to_string(leg + 1) + " passes within " +
                                    std::to_string(clearance) + " m of " +
                                    truth.map().classes[static_cast<std::size_t>(label)].name +
                                    (door >= 0 ? " (not open throughout)" : "") + " at " + where(p));
          reported = true;
        }
      }
    }
  }
  return result;
}

}  // namespace slamer

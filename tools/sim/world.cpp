#include "tools/sim/world.hpp"

#include <cmath>
#include <deque>
#include <limits>

namespace slamer {
namespace {

constexpr int32_t kClassObjectBase = 1'000'000;  // object ids of non-door labelled cells: base + class
constexpr int32_t kTruthObjectBase = 2'000'000;  // truth objects: base + index
constexpr int32_t kWallObject = 3'000'000;       // occupied cells without a label

Eigen::Vector2d read_point(const ConfigReader& reader, std::string_view key) {
  std::vector<double> xy;
  reader.require(key);
  reader.read(key, &xy, {}, 2);
  return {xy[0], xy[1]};
}

DoorState read_door_state(const ConfigReader& reader, std::string_view key) {
  std::string state = "open";
  reader.read_choice(key, &state, {"open", "closed"});
  return state == "open" ? DoorState::kOpen : DoorState::kClosed;
}

// Calls paint(index) for every cell within thickness / 2 of the segment from-to.
template <class Paint>
void for_cells_along(const GridGeometry& g, const Eigen::Vector2d& from, const Eigen::Vector2d& to, double thickness,
                     Paint paint) {
  const Eigen::Vector2d a = g.to_grid(from);
  const Eigen::Vector2d b = g.to_grid(to);
  const double half = thickness / 2.0 / g.resolution;
  const int x0 = static_cast<int>(std::floor(std::min(a.x(), b.x()) - half));
  const int x1 = static_cast<int>(std::ceil(std::max(a.x(), b.x()) + half));
  const int y0 = static_cast<int>(std::floor(std::min(a.y(), b.y()) - half));
  const int y1 = static_cast<int>(std::ceil(std::max(a.y(), b.y()) + half));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (g.contains(x, y) && distance_to_segment({x + 0.5, y + 0.5}, a, b) <= half) {
        paint(g.index(x, y));
      }
    }
  }
}

}  // namespace

void read_options(const ConfigReader& reader, WorldOptions* o) {
  reader.require("map");
  reader.require("robot");
  reader.read("map", &o->map_path);
  reader.read("robot", &o->robot_path);
  o->map_path = reader.resolve_path(o->map_path);
  o->robot_path = reader.resolve_path(o->robot_path);
  o->start = read_pose(reader, "start", o->start);
  o->path.clear();
  for (const ConfigReader& step_reader : reader.list("path")) {
    PathStep step;
    const int kinds =
        (step_reader.has("go_to") ? 1 : 0) + (step_reader.has("turn_to") ? 1 : 0) + (step_reader.has("wait") ? 1 : 0);
    if (kinds != 1) {
      step_reader.fail("go_to", "each path step needs exactly one of go_to, turn_to, wait");
    }
    if (step_reader.has("go_to")) {
      step.kind = PathStep::Kind::kGoTo;
      step.target = read_point(step_reader, "go_to");
      step_reader.read("speed", &step.speed, positive());
    } else if (step_reader.has("turn_to")) {
      step.kind = PathStep::Kind::kTurnTo;
      step_reader.read("turn_to", &step.heading, in_range(-2 * M_PI, 2 * M_PI));
      step.heading = wrap_angle(step.heading);
    } else {
      step.kind = PathStep::Kind::kWait;
      step_reader.read("wait", &step.duration, non_negative());
    }
    o->path.push_back(step);
  }
  reader.read("door_classes", &o->door_classes);
  const ConfigReader returns = reader.section("return_probability");
  for (const std::string& name : returns.keys()) {
    double probability = 1.0;
    returns.read(name, &probability, in_range(0.0, 1.0));
    o->return_probability[name] = probability;
  }
  reader.read("door_snap_distance", &o->door_snap_distance, positive());
  const ConfigReader truth = reader.section("truth");
  for (const ConfigReader& door_reader : truth.list("doors")) {
    DoorTruth door;
    door.near = read_point(door_reader, "near");
    if (door_reader.has("state")) {
      door.state = read_door_state(door_reader, "state");
    }
    double last_time = 0.0;
    for (const ConfigReader& change : door_reader.list("changes")) {
      double time = 0.0;
      change.require("at");
      change.read("at", &time, non_negative());
      if (time < last_time) {
        change.fail("at", "changes must be in time order");
      }
      last_time = time;
      change.require("state");
      door.changes.emplace_back(time, read_door_state(change, "state"));
    }
    o->doors.push_back(door);
  }
  for (const ConfigReader& object_reader : truth.list("objects")) {
    TruthObject object;
    object_reader.require("class");
    object_reader.read("class", &object.class_name);
    object.from = read_point(object_reader, "from");
    object.to = read_point(object_reader, "to");
    object_reader.read("thickness", &object.thickness, positive());
    o->objects.push_back(object);
  }
  for (const ConfigReader& area_reader : truth.list("removed")) {
    TruthArea area;
    area.from = read_point(area_reader, "from");
    area.to = read_point(area_reader, "to");
    area_reader.read("thickness", &area.thickness, positive());
    o->removed.push_back(area);
  }
  const ConfigReader reflectance = reader.section("reflectance");
  for (const std::string& name : reflectance.keys()) {
    double value = 0.0;
    reflectance.read(name, &value, in_range(0.0, 1.0));
    o->reflectance[name] = value;
  }
  const ConfigReader intensity = reader.section("intensity");
  intensity.read("scale", &o->intensity.scale, positive());
  intensity.read("falloff", &o->intensity.falloff, positive());
  intensity.read("noise", &o->intensity.noise, in_range(0.0, 1.0));
}

TrueWorld::TrueWorld(SemanticMap map, const WorldOptions& options, const std::string& world_file)
    : map_(std::move(map)) {
  const GridGeometry& g = map_.geometry;
  const std::size_t cells = g.size();
  std::vector<float> class_return(map_.classes.size(), 1.0f);
  std::vector<bool> is_door_class(map_.classes.size(), false);
  for (std::size_t c = 0; c < map_.classes.size(); ++c) {
    const auto it = options.return_probability.find(map_.classes[c].name);
    if (it != options.return_probability.end()) {
      class_return[c] = static_cast<float>(it->second);
    }
    for (const std::string& name : options.door_classes) {
      is_door_class[c] = is_door_class[c] || map_.classes[c].name == name;
    }
  }
  return_probability_.assign(cells, 0.0f);
  object_of_cell_.assign(cells, -1);
  door_of_cell_.assign(cells, -1);
  truth_labels_ = map_.labels;
  for (std::size_t i = 0; i < cells; ++i) {
    const int label = map_.labels[i];
    if (label >= 0 && !is_door_class[static_cast<std::size_t>(label)]) {
      return_probability_[i] = class_return[static_cast<std::size_t>(label)];
      object_of_cell_[i] = kClassObjectBase + label;
    } else if (label < 0 && map_.occupancy[i] == Occupancy::kOccupied) {
      return_probability_[i] = 1.0f;
      object_of_cell_[i] = kWallObject;
    }
  }

  // Door instances: 8-connected components of door-class cells of one class.
  std::vector<int> door_cells_occupied;
  std::vector<int> door_cells_total;
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t start = g.index(x, y);
      const int label = map_.labels[start];
      if (label < 0 || !is_door_class[static_cast<std::size_t>(label)] || door_of_cell_[start] >= 0) {
        continue;
      }
      const int id = static_cast<int>(door_return_.size());
      door_return_.push_back(class_return[static_cast<std::size_t>(label)]);
      door_cells_occupied.push_back(0);
      door_cells_total.push_back(0);
      std::deque<Cell> queue{{x, y}};
      door_of_cell_[start] = id;
      while (!queue.empty()) {
        const Cell cell = queue.front();
        queue.pop_front();
        const std::size_t index = g.index(cell.x, cell.y);
        object_of_cell_[index] = id;
        ++door_cells_total.back();
        door_cells_occupied.back() += map_.occupancy[index] == Occupancy::kOccupied ? 1 : 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = cell.x + dx;
            const int ny = cell.y + dy;
            if (g.contains(nx, ny) && door_of_cell_[g.index(nx, ny)] < 0 && map_.labels[g.index(nx, ny)] == label) {
              door_of_cell_[g.index(nx, ny)] = id;
              queue.push_back({nx, ny});
            }
          }
        }
      }
    }
  }
  // By default the truth is what the map shows: a door drawn occupied is closed.
  door_truth_.resize(door_return_.size());
  for (std::size_t d = 0; d < door_truth_.size(); ++d) {
    door_truth_[d].state = 2 * door_cells_occupied[d] > door_cells_total[d] ? DoorState::kClosed : DoorState::kOpen;
  }
  for (std::size_t i = 0; i < options.doors.size(); ++i) {
    const DoorTruth& truth = options.doors[i];
    int door = -1;
    double best = options.door_snap_distance;
    const int reach = static_cast<int>(std::ceil(options.door_snap_distance / g.resolution)) + 1;
    const Eigen::Vector2d grid = g.to_grid(truth.near);
    for (int y = static_cast<int>(grid.y()) - reach; y <= static_cast<int>(grid.y()) + reach; ++y) {
      for (int x = static_cast<int>(grid.x()) - reach; x <= static_cast<int>(grid.x()) + reach; ++x) {
        if (g.contains(x, y) && door_of_cell_[g.index(x, y)] >= 0) {
          const double d = (g.cell_center(x, y) - truth.near).norm();
          if (d <= best) {
            best = d;
            door = door_of_cell_[g.index(x, y)];
          }
        }
      }
    }
    if (door < 0) {
      throw ConfigError(world_file + ": truth.doors[" + std::to_string(i) + "]: no door within " +
                        std::to_string(options.door_snap_distance) + " m of (" + std::to_string(truth.near.x()) + ", " +
                        std::to_string(truth.near.y()) + ")");
    }
    DoorTruth& target = door_truth_[static_cast<std::size_t>(door)];
    target.near = truth.near;
    if (truth.state) {
      target.state = truth.state;
    }
    target.changes = truth.changes;
  }

  // Objects of the true world that the map does not show.
  for (std::size_t i = 0; i < options.objects.size(); ++i) {
    const TruthObject& object = options.objects[i];
    const int label = map_.class_index(object.class_name);
    if (label < 0) {
      throw ConfigError(world_file + ": truth.objects[" + std::to_string(i) + "]: class '" + object.class_name +
                        "' is not in the map's class table");
    }
    for_cells_along(g, object.from, object.to, object.thickness, [&](std::size_t index) {
      return_probability_[index] = class_return[static_cast<std::size_t>(label)];
      object_of_cell_[index] = kTruthObjectBase + static_cast<int32_t>(i);
      door_of_cell_[index] = -1;
      truth_labels_[index] = static_cast<int8_t>(label);
    });
  }
  // Objects of the map that the true world no longer has.
  for (const TruthArea& area : options.removed) {
    for_cells_along(g, area.from, area.to, area.thickness, [&](std::size_t index) {
      return_probability_[index] = 0.0f;
      object_of_cell_[index] = -1;
      door_of_cell_[index] = -1;
      truth_labels_[index] = -1;
    });
  }
  // Reflectance per cell of what the true world has there.
  if (!options.reflectance.empty()) {
    std::vector<float> class_reflectance(map_.classes.size(), 0.5f);
    const auto others = options.reflectance.find("others");
    const float unlabelled = others != options.reflectance.end() ? static_cast<float>(others->second) : 0.5f;
    for (std::size_t c = 0; c < map_.classes.size(); ++c) {
      const auto it = options.reflectance.find(map_.classes[c].name);
      class_reflectance[c] = it != options.reflectance.end() ? static_cast<float>(it->second) : unlabelled;
    }
    reflectance_.assign(cells, unlabelled);
    for (std::size_t i = 0; i < cells; ++i) {
      if (truth_labels_[i] >= 0) {
        reflectance_[i] = class_reflectance[static_cast<std::size_t>(truth_labels_[i])];
      }
    }
  }
}

DoorState TrueWorld::door_state(int door, double time) const {
  const DoorTruth& truth = door_truth_[static_cast<std::size_t>(door)];
  DoorState state = *truth.state;
  for (const auto& [at, new_state] : truth.changes) {
    if (time >= at) {
      state = new_state;
    }
  }
  return state;
}

int TrueWorld::door_at(const Eigen::Vector2d& world) const {
  const std::optional<Cell> cell = map_.geometry.cell_at(world);
  return cell ? door_of_cell_[map_.geometry.index(cell->x, cell->y)] : -1;
}

double TrueWorld::cast(const Eigen::Vector2d& origin, double angle, double max_range, double time, std::mt19937& rng,
                       float* reflectance) const {
  const GridGeometry& g = map_.geometry;
  const Eigen::Vector2d start = g.to_grid(origin);
  const double grid_angle = angle - g.origin.theta;
  const double dx = std::cos(grid_angle);
  const double dy = std::sin(grid_angle);
  int x = static_cast<int>(std::floor(start.x()));
  int y = static_cast<int>(std::floor(start.y()));
  const int step_x = dx >= 0.0 ? 1 : -1;
  const int step_y = dy >= 0.0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double delta_x = dx != 0.0 ? std::abs(1.0 / dx) : kInf;
  const double delta_y = dy != 0.0 ? std::abs(1.0 / dy) : kInf;
  double next_x = dx != 0.0 ? ((x + (step_x > 0 ? 1 : 0)) - start.x()) / dx : kInf;
  double next_y = dy != 0.0 ? ((y + (step_y > 0 ? 1 : 0)) - start.y()) / dy : kInf;
  const double max_t = max_range / g.resolution;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double t = 0.0;  // ray parameter [cells] where the current cell was entered
  int32_t current_object = -1;
  while (t <= max_t) {
    if (!g.contains(x, y)) {
      return kInf;  // the map is the world: nothing beyond it
    }
    const std::size_t index = g.index(x, y);
    const int32_t object = object_of_cell_[index];
    if (object != current_object) {
      current_object = object;
      float probability = return_probability_[index];
      const int door = door_of_cell_[index];
      if (door >= 0) {
        probability =
            door_state(door, time) == DoorState::kClosed ? door_return_[static_cast<std::size_t>(door)] : 0.0f;
      }
      if (probability >= 1.0f || (probability > 0.0f && uniform(rng) < probability)) {
        if (reflectance != nullptr) {
          *reflectance = reflectance_.empty() ? 0.0f : reflectance_[index];
        }
        return t * g.resolution;
      }
    }
    if (next_x < next_y) {
      t = next_x;
      next_x += delta_x;
      x += step_x;
    } else {
      t = next_y;
      next_y += delta_y;
      y += step_y;
    }
  }
  return kInf;
}

int TrueWorld::class_near(const Eigen::Vector2d& world, double radius, int* door) const {
  const GridGeometry& g = map_.geometry;
  const Eigen::Vector2d grid = g.to_grid(world);
  const int reach = static_cast<int>(std::ceil(radius / g.resolution));
  int best_label = -1;
  int best_door = -1;
  double best = radius;
  for (int y = static_cast<int>(std::floor(grid.y())) - reach; y <= static_cast<int>(std::floor(grid.y())) + reach;
       ++y) {
    for (int x = static_cast<int>(std::floor(grid.x())) - reach; x <= static_cast<int>(std::floor(grid.x())) + reach;
         ++x) {
      if (g.contains(x, y) && truth_labels_[g.index(x, y)] >= 0) {
        const double d = (g.cell_center(x, y) - world).norm();
        if (d <= best) {
          best = d;
          best_label = truth_labels_[g.index(x, y)];
          best_door = door_of_cell_[g.index(x, y)];
        }
      }
    }
  }
  if (door != nullptr) {
    *door = best_door;
  }
  return best_label;
}

}  // namespace slamer

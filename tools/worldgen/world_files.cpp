#include "tools/worldgen/world_files.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "tools/sim/floor_plan.hpp"

namespace slamer {
namespace {

const char* state_name(DoorState s) {
  return s == DoorState::kOpen ? "open" : "closed";
}

std::string xy(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4) << "[" << p.x() << ", " << p.y() << "]";
  return out.str();
}

std::string changes_text(const BuildingDoor& door) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << "[";
  for (std::size_t i = 0; i < door.changes.size(); ++i) {
    out << (i > 0 ? ", " : "") << "{at: " << door.changes[i].first << ", state: " << state_name(door.changes[i].second)
        << "}";
  }
  out << "]";
  return out.str();
}

void save(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  if (!file) {
    throw std::runtime_error("cannot write " + path);
  }
}

FloorPlan floor_plan(const Building& b, double resolution) {
  FloorPlan plan;
  plan.resolution = resolution;
  Eigen::Vector2d high(0.0, 0.0);
  for (const auto& polygon : b.footprint) {
    for (const Eigen::Vector2d& p : polygon) {
      high = high.cwiseMax(p);
    }
  }
  plan.origin = {0.0, 0.0};
  plan.size = {std::ceil(high.x() + 2.0), std::ceil(high.y() + 2.0)};
  plan.unknown_background = true;
  plan.free_polygons = b.footprint;
  plan.classes = {{"door", {255, 0, 255}, true},
                  {"glass_door", {0, 255, 255}, true},
                  {"fence", {255, 128, 0}, true},
                  {"no_entry_line", {255, 0, 0}, false},
                  {"others", {0, 0, 0}, true}};
  for (const BuildingShape& s : b.shapes) {
    plan.shapes.push_back({s.class_name, s.width, s.occupied, {s.a, s.b}});
  }
  for (const BuildingDoor& d : b.doors) {
    plan.shapes.push_back({d.class_name, d.thickness, d.map_state == DoorState::kClosed, {d.a, d.b}});
  }
  return plan;
}

std::string plan_text(const FloorPlan& plan, uint64_t seed) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4);
  out << "# A building made by slamer-gen-world --seed " << seed << "; render with slamer-make-map plan.yaml .\n"
      << "resolution: " << plan.resolution << "\nsize: " << xy(plan.size) << "\norigin: " << xy(plan.origin)
      << "\nunknown_background: true\nfree_areas:\n";
  for (const auto& polygon : plan.free_polygons) {
    out << "  - {polygon: [";
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      out << (i > 0 ? ", " : "") << polygon[i].x() << ", " << polygon[i].y();
    }
    out << "]}\n";
  }
  out << "classes:\n";
  for (const PlanClass& c : plan.classes) {
    out << "  - {name: " << c.name << ", color: [" << int{c.rgb[0]} << ", " << int{c.rgb[1]} << ", " << int{c.rgb[2]}
        << "]" << (c.occupied ? "" : ", occupied: false") << "}\n";
  }
  out << "shapes:\n";
  for (const PlanShape& s : plan.shapes) {
    out << "  - {class: " << s.class_name << ", width: " << s.width << ", occupied: " << (s.occupied ? "true" : "false")
        << ", points: [" << s.points[0].x() << ", " << s.points[0].y() << ", " << s.points[1].x() << ", "
        << s.points[1].y() << "]}\n";
  }
  return out.str();
}

std::string world_text(const Building& b, uint64_t seed) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4);
  out << "# A world made by slamer-gen-world --seed " << seed << " (map, route, materials, truth).\n"
      << "map: map.yaml\nrobot: robot.yaml\nstart: [" << b.start.x << ", " << b.start.y << ", " << b.start.theta
      << "]\npath:\n";
  for (const PathStep& s : b.path) {
    if (s.kind == PathStep::Kind::kGoTo) {
      out << "  - {go_to: " << xy(s.target) << ", speed: " << s.speed << "}\n";
    } else if (s.kind == PathStep::Kind::kWait) {
      out << "  - {wait: " << s.duration << "}\n";
    }
  }
  out << "return_probability:\n";
  for (const auto& [name, p] : b.return_probability) {
    out << "  " << name << ": " << p << "\n";
  }
  out << "reflectance:   # laser intensities (the URG's) follow it\n";
  for (const auto& [name, r] : b.reflectance) {
    out << "  " << name << ": " << r << "\n";
  }
  out << "truth:\n  doors:\n";
  for (const BuildingDoor& d : b.doors) {
    out << "    - {near: " << xy((d.a + d.b) / 2.0) << ", state: " << state_name(d.truth_state)
        << ", changes: " << changes_text(d) << "}   # map: " << state_name(d.map_state) << "\n";
  }
  out << "  objects:\n";
  for (const TruthObject& o : b.added) {
    out << "    - {class: " << o.class_name << ", from: " << xy(o.from) << ", to: " << xy(o.to)
        << ", thickness: " << o.thickness << "}\n";
  }
  out << "  removed:\n";
  for (const TruthArea& a : b.removed) {
    out << "    - {from: " << xy(a.from) << ", to: " << xy(a.to) << ", thickness: " << a.thickness << "}\n";
  }
  return out.str();
}

std::string differences_text(const Building& b, uint64_t seed) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4);
  out << "# Where the truth of world.yaml differs from the map (slamer-gen-world --seed " << seed << ").\n"
      << "seed: " << seed << "\nduration_estimate: " << b.duration_estimate << "\ndoors:\n";
  for (const BuildingDoor& d : b.doors) {
    out << "  - {class: " << d.class_name << ", center: " << xy((d.a + d.b) / 2.0) << ", width: " << (d.b - d.a).norm()
        << ", framed: " << (d.framed ? "true" : "false") << ", hinged: " << (d.hinged ? "true" : "false")
        << ", on_route: " << (d.on_route ? "true" : "false") << ", map: " << state_name(d.map_state)
        << ", truth: " << state_name(d.truth_state) << ", changes: " << changes_text(d) << "}\n";
  }
  out << "added: " << b.added.size() << "     # objects in the truth only (world.yaml truth.objects)\n"
      << "removed: " << b.removed.size() << "   # objects in the map only (world.yaml truth.removed)\n";
  return out.str();
}

}  // namespace

void write_world(const Building& building, const WorldGenOptions& options, uint64_t seed, const std::string& robot_file,
                 const std::string& directory) {
  std::filesystem::create_directories(directory);
  const FloorPlan plan = floor_plan(building, options.resolution);
  save(directory + "/plan.yaml", plan_text(plan, seed));
  write_floor_plan_map(plan, directory);
  save(directory + "/world.yaml", world_text(building, seed));
  save(directory + "/differences.yaml", differences_text(building, seed));
  std::ifstream robot(robot_file, std::ios::binary);
  if (!robot) {
    throw std::runtime_error("cannot read the robot file " + robot_file);
  }
  save(directory + "/robot.yaml", std::string(std::istreambuf_iterator<char>(robot), {}));
}

void read_options(const ConfigReader& reader, MapDifferences* d) {
  reader.read("seed", &d->seed, non_negative());
  reader.read("duration_estimate", &d->duration_estimate, non_negative());
  for (const ConfigReader& entry : reader.list("doors")) {
    MapDifferences::Door door;
    entry.read("class", &door.class_name);
    std::vector<double> center;
    entry.read("center", &center, {}, 2);
    door.center = {center[0], center[1]};
    entry.read("width", &door.width, positive());
    entry.read("framed", &door.framed);
    entry.read("hinged", &door.hinged);
    entry.read("on_route", &door.on_route);
    entry.read_choice("map", &door.map_state, {"open", "closed"});
    entry.read_choice("truth", &door.truth_state, {"open", "closed"});
    for (const ConfigReader& change : entry.list("changes")) {
      double at = 0.0;
      std::string state = "open";
      change.read("at", &at, non_negative());
      change.read_choice("state", &state, {"open", "closed"});
      door.changes.emplace_back(at, state);
    }
    d->doors.push_back(door);
  }
  reader.read("added", &d->added, non_negative());
  reader.read("removed", &d->removed, non_negative());
}

}  // namespace slamer

#include "tools/worldgen/building.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "tools/worldgen/placement.hpp"

namespace slamer {
namespace {

using Vec = Eigen::Vector2d;

struct Room {
  double a = 0.0, b = 0.0, depth = 0.0;
  bool north = false;
  double door_x = 0.0;
  int door = -1;
  // The room's interior between y_near (the corridor wall) and y_far.
  double y_near(double corridor_width) const { return north ? corridor_width : 0.0; }
  double y_far(double corridor_width) const { return north ? corridor_width + depth : -depth; }
  double y_mid(double corridor_width) const { return (y_near(corridor_width) + y_far(corridor_width)) / 2.0; }
};

class Generator {
 public:
  Generator(const WorldGenOptions& options, uint64_t seed) : o_(options) {
    std::seed_seq seq{seed, uint64_t{11}};
    rng_.seed(seq);
  }

  Building run() {
    length_ = uniform(o_.corridor.length_min, o_.corridor.length_max);
    width_ = uniform(o_.corridor.width_min, o_.corridor.width_max);
    wall_ = uniform(o_.rooms.wall_min, o_.rooms.wall_max);
    materials();
    for (const bool north : {false, true}) {
      make_rooms(north);
    }
    corridor();
    std::vector<int> visited = route_rooms();
    for (Room& room : rooms_) {
      room_contents(room);
    }
    door_truth();
    corridor_cabinets();
    removed_and_added();
    route(visited);
    turn();
    return std::move(b_);
  }

 private:
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  void add(const std::string& c, Vec a, Vec b, double width, bool occupied = true) {
    b_.shapes.push_back({c, a, b, width, occupied});
  }

  void materials() {
    b_.return_probability = {{"door", 1.0},
                             {"glass_door", uniform(0.2, 0.4)},
                             {"fence", uniform(0.25, 0.6)},
                             {"no_entry_line", 0.0},
                             {"others", 1.0}};
    b_.reflectance = {{"door", uniform(0.3, 0.8)},
                      {"glass_door", uniform(0.05, 0.15)},
                      {"fence", uniform(0.5, 0.9)},
                      {"no_entry_line", 0.0},
                      {"others", uniform(0.4, 0.7)}};
  }

  void make_rooms(bool north) {
    double x = 0.0;
    while (length_ - x > 1e-6) {
      double w = uniform(o_.rooms.width_min, o_.rooms.width_max);
      if (length_ - x - w < o_.rooms.width_min) {
        w = length_ - x;
      }
      Room room{x, x + w, uniform(o_.rooms.depth_min, o_.rooms.depth_max), north};
      const double door_width = uniform(o_.doors.width_min, std::min(o_.doors.width_max, w - 1.0));
      room.door_x = uniform(room.a + 0.5 + door_width / 2.0, room.b - 0.5 - door_width / 2.0);
      room.door = add_door(chance(o_.doors.glass_probability) ? "glass_door" : "door", room.door_x, room.y_near(width_),
                           door_width, true);
      const double y0 = room.y_near(width_);
      const double y1 = room.y_far(width_);
      add("others", {room.a, y0}, {room.a, y1}, wall_);
      add("others", {room.b, y0}, {room.b, y1}, wall_);
      add("others", {room.a, y1}, {room.b, y1}, wall_);
      if (chance(o_.rooms.chamfer_probability)) {  // a diagonal wall across a far corner
        const double c = uniform(0.8, std::max(0.9, std::min({2.0, room.depth / 2.0 - 0.6, (w - 1.0) / 2.0})));
        const double corner_x = chance(0.5) ? room.a : room.b;
        const double sx = corner_x == room.a ? 1.0 : -1.0;
        const double sy = north ? -1.0 : 1.0;
        add("others", {corner_x + sx * c, y1}, {corner_x, y1 + sy * c}, wall_);
      }
      b_.footprint.push_back(rectangle(room.a - wall_ / 2, std::min(y0, y1) - wall_ / 2, room.b + wall_ / 2,
                                       std::max(y0, y1) + wall_ / 2));
      rooms_.push_back(room);
      x += w;
    }
  }

  // A door in a wall along x at height y (horizontal) or in the corridor's end (vertical).
  int add_door(const std::string& c, double along, double at, double width, bool horizontal) {
    BuildingDoor door;
    door.class_name = c;
    door.framed = chance(o_.doors.frame_probability);
    door.hinged = chance(o_.doors.hinged_probability);
    door.thickness = door.framed ? 0.1 : wall_;
    door.map_state = chance(o_.doors.closed_in_map_probability) ? DoorState::kClosed : DoorState::kOpen;
    const auto point = [&](double u, double v) { return horizontal ? Vec(u, v) : Vec(v, u); };
    door.a = point(along - width / 2.0, at);
    door.b = point(along + width / 2.0, at);
    if (door.framed) {  // jambs protruding 8 cm on both sides of the wall
      for (const double u : {along - width / 2.0 - 0.05, along + width / 2.0 + 0.05}) {
        add("others", point(u, at - wall_ / 2 - 0.08), point(u, at + wall_ / 2 + 0.08), 0.1);
      }
    }
    b_.doors.push_back(door);
    gaps_[{horizontal, at}].emplace_back(along - width / 2.0, along + width / 2.0);
    return static_cast<int>(b_.doors.size()) - 1;
  }

  void corridor() {
    for (const double x : {0.0, length_}) {
      if (chance(o_.corridor.end_glass_door_probability)) {
        const double w = uniform(0.9, std::min(o_.doors.width_max, width_ - 0.4));
        const int d = add_door("glass_door", uniform(w / 2 + 0.2, width_ - w / 2 - 0.2), x, w, false);
        b_.doors[static_cast<std::size_t>(d)].map_state = DoorState::kClosed;
      }
    }
    // Walls with gaps where the doors are.
    for (auto& [line, gaps] : gaps_) {
      const bool horizontal = line.first;
      const double at = line.second;
      std::sort(gaps.begin(), gaps.end());
      double from = 0.0;
      const double to = horizontal ? length_ : width_;
      for (const auto& [g0, g1] : gaps) {
        add_wall_piece(horizontal, at, from, g0);
        from = g1;
      }
      add_wall_piece(horizontal, at, from, to);
    }
    for (const bool north : {false, true}) {
      if (gaps_.count({true, north ? width_ : 0.0}) == 0) {
        add_wall_piece(true, north ? width_ : 0.0, 0.0, length_);
      }
    }
    for (const double x : {0.0, length_}) {
      if (gaps_.count({false, x}) == 0) {
        add_wall_piece(false, x, 0.0, width_);
      }
    }
    b_.footprint.push_back(rectangle(-wall_ / 2, -wall_ / 2, length_ + wall_ / 2, width_ + wall_ / 2));
    route_end_ = length_ - 1.5;
    if (chance(o_.corridor.no_entry_probability)) {
      const double x = length_ - uniform(2.0, 5.0);
      add("no_entry_line", {x, 0.0}, {x, width_}, 0.1, false);
      route_end_ = x - 1.0;
      keep_out_.push_back({{x, 0.0}, {x, width_}, 0.3});
    }
  }

  void add_wall_piece(bool horizontal, double at, double u0, double u1) {
    if (u1 - u0 > 1e-6) {
      add("others", horizontal ? Vec(u0, at) : Vec(at, u0), horizontal ? Vec(u1, at) : Vec(at, u1), wall_);
    }
  }

  std::vector<int> route_rooms() {
    route_end_ = 1.5 + o_.route.corridor_fraction * (route_end_ - 1.5);
    std::vector<int> candidates;
    for (std::size_t i = 0; i < rooms_.size(); ++i) {
      const BuildingDoor& door = b_.doors[static_cast<std::size_t>(rooms_[i].door)];
      if (rooms_[i].door_x > 2.0 && rooms_[i].door_x < route_end_ - 0.3 && (door.b - door.a).norm() >= 0.8) {
        candidates.push_back(static_cast<int>(i));
      }
    }
    std::shuffle(candidates.begin(), candidates.end(), rng_);
    const int count =
        std::min<int>(integer(o_.route.rooms_min, o_.route.rooms_max), static_cast<int>(candidates.size()));
    candidates.resize(static_cast<std::size_t>(std::max(0, count)));
    std::sort(candidates.begin(), candidates.end(), [&](int i, int j) {
      return rooms_[static_cast<std::size_t>(i)].door_x < rooms_[static_cast<std::size_t>(j)].door_x;
    });
    for (const int i : candidates) {
      const Room& room = rooms_[static_cast<std::size_t>(i)];
      b_.doors[static_cast<std::size_t>(room.door)].on_route = true;
      entered_.push_back(i);
    }
    // The corridor's centre line is kept clear everywhere.
    keep_out_.push_back({{0.5, width_ / 2}, {length_ - 0.5, width_ / 2}, 0.5});
    return candidates;
  }

  void room_contents(Room& room) {
    const double y0 = room.y_near(width_);
    const double y1 = room.y_far(width_);
    const BuildingDoor& door = b_.doors[static_cast<std::size_t>(room.door)];
    const double door_width = (door.b - door.a).norm();
    Placement place(room.a + wall_ / 2, std::min(y0, y1) + wall_ / 2, room.b - wall_ / 2, std::max(y0, y1) - wall_ / 2);
    for (const KeepOut& k : keep_out_) {
      place.reserve(k);
    }
    // The way in (every room's: any may be on the route of a later variant) and a swung leaf.
    const Vec inside(room.door_x, room.y_mid(width_));
    place.reserve({{room.door_x, y0}, inside, 0.55});
    place.reserve({inside, inside, 0.9});
    const double sy = room.north ? 1.0 : -1.0;
    for (const double u : {room.door_x - door_width / 2, room.door_x + door_width / 2}) {
      place.reserve({{u, y0}, {u, y0 + sy * std::min(door_width, room.depth - 0.5)}, 0.1});
    }
    const int furniture = integer(0, o_.rooms.furniture_max);
    for (int i = 0; i < furniture; ++i) {
      if (auto s = place.random_segment(rng_, 0.5, 1.6, uniform(0.4, 0.8), 0.6)) {
        furniture_.push_back(static_cast<int>(b_.shapes.size()));
        add("others", s->a, s->b, s->half * 2);
      }
    }
    if (chance(o_.rooms.fence_probability)) {
      if (auto s = place.random_segment(rng_, 1.0, 4.0, 0.1, 0.7)) {
        add("fence", s->a, s->b, 0.1);
      }
    }
    if (chance(o_.rooms.no_entry_probability)) {
      if (auto s = place.random_segment(rng_, 1.0, 8.0, 0.1, 0.7)) {
        add("no_entry_line", s->a, s->b, 0.1, false);
      }
    }
    if (chance(o_.differences.room_object_probability)) {
      if (auto s = place.random_segment(rng_, 0.5, 1.4, uniform(0.4, 0.7), 0.5)) {
        b_.added.push_back({"others", s->a, s->b, s->half * 2});
      }
    }
  }

  void door_truth() {
    for (BuildingDoor& door : b_.doors) {
      const DoorState other = door.map_state == DoorState::kOpen ? DoorState::kClosed : DoorState::kOpen;
      door.truth_state = door.map_state;
      if (door.on_route) {
        door.truth_state = DoorState::kOpen;
        continue;
      }
      const double r = uniform(0.0, 1.0);
      if (r < o_.differences.flip_probability) {
        door.truth_state = other;
      } else if (r < o_.differences.flip_probability + o_.differences.change_probability) {
        door.changes.emplace_back(-1.0, other);  // time set once the route is known
      }
    }
  }

  void corridor_cabinets() {
    const int count = integer(o_.differences.corridor_objects_min, o_.differences.corridor_objects_max);
    for (int i = 0, tries = 0; i < count && tries < 50; ++tries) {
      const bool north = chance(0.5);
      const double depth = uniform(0.3, std::max(0.31, std::min(0.5, width_ / 2 - wall_ / 2 - 0.5)));
      const double length = uniform(0.6, 1.5);
      const double x = uniform(2.0, length_ - 2.0 - length);
      bool clear = true;
      for (const BuildingDoor& door : b_.doors) {
        const double lo = std::min(door.a.x(), door.b.x()) - 0.6;
        const double hi = std::max(door.a.x(), door.b.x()) + 0.6;
        clear = clear && (x + length < lo || x > hi);
      }
      if (!clear) {
        continue;
      }
      const double y = north ? width_ - wall_ / 2 - 0.03 - depth / 2 : wall_ / 2 + 0.03 + depth / 2;
      b_.added.push_back({"others", {x, y}, {x + length, y}, depth});
      ++i;
    }
  }

  void removed_and_added() {
    if (!furniture_.empty() && chance(o_.differences.removed_probability)) {
      const BuildingShape& s = b_.shapes[static_cast<std::size_t>(
          furniture_[static_cast<std::size_t>(integer(0, static_cast<int>(furniture_.size()) - 1))])];
      b_.removed.push_back({s.a, s.b, s.width + 0.1});
    }
  }

  void route(const std::vector<int>& visited) {
    const double v = o_.route.speed;
    const double y = width_ / 2;
    b_.start = {1.5, y, 0.0};
    Vec at(1.5, y);
    double length = 0.0;
    const auto go = [&](Vec p) {
      PathStep step;
      step.kind = PathStep::Kind::kGoTo;
      step.target = p;
      step.speed = v;
      b_.path.push_back(step);
      length += (p - at).norm();
      at = p;
      b_.duration_estimate += 3.0;  // the turn before it
    };
    for (const int i : visited) {
      const Room& room = rooms_[static_cast<std::size_t>(i)];
      go({room.door_x, y});
      go({room.door_x, room.y_mid(width_)});
      PathStep wait;
      wait.kind = PathStep::Kind::kWait;
      wait.duration = 1.0;
      b_.path.push_back(wait);
      b_.duration_estimate += 1.0;
      go({room.door_x, y});
    }
    go({route_end_, y});
    if (o_.route.return_to_start) {
      go({1.5, y});
    }
    b_.duration_estimate += length / v;
    for (BuildingDoor& door : b_.doors) {
      for (auto& change : door.changes) {
        change.first = std::round(uniform(0.25, 0.75) * b_.duration_estimate * 10.0) / 10.0;
      }
      if (door.hinged && door.changes.empty() && door.truth_state == DoorState::kOpen && door.class_name == "door" &&
          door.a.y() == door.b.y()) {
        // An open hinged leaf stands at right angles into the room, at its hinge.
        const bool north = door.a.y() > width_ / 2;
        const double w = (door.b - door.a).norm();
        const Vec hinge = door.a + Vec(0.05, 0.0);
        b_.added.push_back({"others", hinge, hinge + Vec(0.0, (north ? 1.0 : -1.0) * std::min(w, 2.5)), 0.08});
      }
    }
  }

  // Turns and moves everything so the building stands at a random angle inside positive coordinates.
  void turn() {
    const double angle = chance(o_.rotation_probability) ? uniform(-M_PI, M_PI) : 0.0;
    Pose2 t{0.0, 0.0, angle};
    Vec low(1e9, 1e9);
    for (const auto& polygon : b_.footprint) {
      for (const Vec& p : polygon) {
        low = low.cwiseMin(transform_point(t, p));
      }
    }
    t.x = 2.0 - low.x();
    t.y = 2.0 - low.y();
    const auto f = [&](Vec& p) { p = transform_point(t, p); };
    for (BuildingShape& s : b_.shapes) {
      f(s.a);
      f(s.b);
    }
    for (BuildingDoor& d : b_.doors) {
      f(d.a);
      f(d.b);
    }
    for (TruthObject& o : b_.added) {
      f(o.from);
      f(o.to);
    }
    for (TruthArea& a : b_.removed) {
      f(a.from);
      f(a.to);
    }
    for (auto& polygon : b_.footprint) {
      for (Vec& p : polygon) {
        f(p);
      }
    }
    for (PathStep& s : b_.path) {
      f(s.target);
    }
    b_.start = compose(t, b_.start);
  }

  static std::vector<Vec> rectangle(double x0, double y0, double x1, double y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  }

  const WorldGenOptions& o_;
  std::mt19937 rng_;
  Building b_;
  double length_ = 0.0, width_ = 0.0, wall_ = 0.0, route_end_ = 0.0;
  std::vector<Room> rooms_;
  std::vector<int> entered_;
  std::vector<int> furniture_;  // indices into shapes
  std::vector<KeepOut> keep_out_;
  std::map<std::pair<bool, double>, std::vector<std::pair<double, double>>> gaps_;
};

}  // namespace

Building generate_building(const WorldGenOptions& options, uint64_t seed) {
  return Generator(options, seed).run();
}

}  // namespace slamer

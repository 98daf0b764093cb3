#include "tools/worldgen/building.hpp"

namespace slamer {
namespace {

void read_range(const ConfigReader& r, std::string_view lo_key, std::string_view hi_key, double* lo, double* hi,
                NumberRule rule) {
  r.read(lo_key, lo, rule);
  r.read(hi_key, hi, rule);
  if (*lo > *hi) {
    r.fail(hi_key, "must not be below " + std::string(lo_key));
  }
}

}  // namespace

void read_options(const ConfigReader& reader, WorldGenOptions* o) {
  const ConfigReader corridor = reader.section("corridor");
  read_range(corridor, "length_min", "length_max", &o->corridor.length_min, &o->corridor.length_max,
             in_range(8.0, 200.0));
  read_range(corridor, "width_min", "width_max", &o->corridor.width_min, &o->corridor.width_max, in_range(1.8, 6.0));
  corridor.read("end_glass_door_probability", &o->corridor.end_glass_door_probability, probability());
  corridor.read("no_entry_probability", &o->corridor.no_entry_probability, probability());
  const ConfigReader rooms = reader.section("rooms");
  read_range(rooms, "width_min", "width_max", &o->rooms.width_min, &o->rooms.width_max, in_range(2.8, 30.0));
  read_range(rooms, "depth_min", "depth_max", &o->rooms.depth_min, &o->rooms.depth_max, in_range(3.0, 30.0));
  read_range(rooms, "wall_min", "wall_max", &o->rooms.wall_min, &o->rooms.wall_max, in_range(0.1, 0.5));
  rooms.read("chamfer_probability", &o->rooms.chamfer_probability, probability());
  rooms.read("furniture_max", &o->rooms.furniture_max, in_range(0, 20));
  rooms.read("fence_probability", &o->rooms.fence_probability, probability());
  rooms.read("no_entry_probability", &o->rooms.no_entry_probability, probability());
  const ConfigReader doors = reader.section("doors");
  read_range(doors, "width_min", "width_max", &o->doors.width_min, &o->doors.width_max, in_range(0.6, 1.8));
  doors.read("frame_probability", &o->doors.frame_probability, probability());
  doors.read("glass_probability", &o->doors.glass_probability, probability());
  doors.read("hinged_probability", &o->doors.hinged_probability, probability());
  doors.read("closed_in_map_probability", &o->doors.closed_in_map_probability, probability());
  const ConfigReader d = reader.section("differences");
  d.read("flip_probability", &o->differences.flip_probability, probability());
  d.read("change_probability", &o->differences.change_probability, probability());
  if (o->differences.flip_probability + o->differences.change_probability > 1.0) {
    d.fail("change_probability", "flip_probability + change_probability must not exceed 1");
  }
  d.read("corridor_objects_min", &o->differences.corridor_objects_min, in_range(0, 20));
  d.read("corridor_objects_max", &o->differences.corridor_objects_max, in_range(0, 20));
  if (o->differences.corridor_objects_min > o->differences.corridor_objects_max) {
    d.fail("corridor_objects_max", "must not be below corridor_objects_min");
  }
  d.read("room_object_probability", &o->differences.room_object_probability, probability());
  d.read("removed_probability", &o->differences.removed_probability, probability());
  const ConfigReader route = reader.section("route");
  route.read("rooms_min", &o->route.rooms_min, in_range(0, 50));
  route.read("rooms_max", &o->route.rooms_max, in_range(0, 50));
  if (o->route.rooms_min > o->route.rooms_max) {
    route.fail("rooms_max", "must not be below rooms_min");
  }
  route.read("speed", &o->route.speed, in_range(0.05, 2.0));
  route.read("corridor_fraction", &o->route.corridor_fraction, in_range(0.05, 1.0));
  route.read("return_to_start", &o->route.return_to_start);
  reader.read("rotation_probability", &o->rotation_probability, probability());
  reader.read("resolution", &o->resolution, in_range(0.01, 0.2));
}

}  // namespace slamer

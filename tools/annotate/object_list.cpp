#include "tools/annotate/object_list.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tools/annotate/object_cells.hpp"

namespace slamer {
namespace {

std::string class_names(const std::vector<SemanticClass>& classes) {
  std::string text;
  for (const SemanticClass& c : classes) {
    text += (text.empty() ? "" : ", ") + c.name;
  }
  return text;
}

bool reserved(const std::array<uint8_t, 3>& rgb) {
  // The semantic image's unknown / free / unlabelled colours (semantic_map.cpp).
  return rgb == std::array<uint8_t, 3>{205, 205, 205} || rgb == std::array<uint8_t, 3>{254, 254, 254} ||
         rgb == std::array<uint8_t, 3>{255, 255, 255};
}

// Adds `c` unless the table has its name; a colour another class has is an error (reported by `fail`).
template <typename Fail>
void add_class(const SemanticClass& c, std::vector<SemanticClass>* table, Fail fail) {
  if (std::any_of(table->begin(), table->end(), [&](const SemanticClass& k) { return k.name == c.name; })) {
    return;
  }
  const auto same = std::find_if(table->begin(), table->end(), [&](const SemanticClass& k) { return k.rgb == c.rgb; });
  if (same != table->end()) {
    fail("class '" + c.name + "' has the colour of class '" + same->name + "'");
  }
  table->push_back(c);
}

// A project class whose colour the map's table already uses gets the next free one.
SemanticClass with_free_colour(SemanticClass c, const std::vector<SemanticClass>& table) {
  const auto taken = [&](const std::array<uint8_t, 3>& rgb) {
    return reserved(rgb) ||
           std::any_of(table.begin(), table.end(), [&](const SemanticClass& k) { return k.rgb == rgb; });
  };
  for (int step = 0; step < 256 * 256 && taken(c.rgb); ++step) {
    c.rgb[2] = static_cast<uint8_t>(c.rgb[2] + 1);
    if (c.rgb[2] == 0) {
      c.rgb[1] = static_cast<uint8_t>(c.rgb[1] + 1);
    }
  }
  return c;
}

std::vector<SemanticClass> read_classes(const ConfigReader& reader, const SemanticMap& map) {
  std::vector<SemanticClass> table = map.classes;
  for (const SemanticClass& c : project_classes()) {
    if (table.size() < 127) {
      add_class(with_free_colour(c, table), &table, [](const std::string&) {});
    }
  }
  for (const ConfigReader& entry : reader.list("classes")) {
    SemanticClass c;
    entry.require("name");
    entry.read("name", &c.name);
    if (c.name.empty() ||
        c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
            std::string::npos) {
      entry.fail("name", "'" + c.name + "': a class name is letters, digits, '_', '-' and '.'");
    }
    if (std::any_of(table.begin(), table.end(), [&](const SemanticClass& k) { return k.name == c.name; })) {
      entry.fail("name", "'" + c.name + "' is already a class (" + class_names(table) + ")");
    }
    std::vector<double> rgb;
    entry.require("color");
    entry.read("color", &rgb, in_range(0, 255), 3);
    for (const double v : rgb) {
      if (v != std::floor(v)) {
        entry.fail("color", "colour components must be integers in [0, 255]");
      }
    }
    c.rgb = {static_cast<uint8_t>(rgb[0]), static_cast<uint8_t>(rgb[1]), static_cast<uint8_t>(rgb[2])};
    if (reserved(c.rgb)) {
      entry.fail("color", "is reserved for unknown (205), free (254) or unlabelled (255) cells");
    }
    add_class(c, &table, [&](const std::string& problem) { entry.fail("color", problem); });
  }
  if (table.size() > 127) {
    reader.fail("classes", "at most 127 classes are supported");
  }
  return table;
}

std::string describe_extent(const GridGeometry& g) {
  char text[160];
  if (g.origin.theta == 0.0) {
    std::snprintf(text, sizeof text, "x %.2f .. %.2f, y %.2f .. %.2f m", g.origin.x,
                  g.origin.x + g.width * g.resolution, g.origin.y, g.origin.y + g.height * g.resolution);
  } else {
    std::snprintf(text, sizeof text, "%d x %d cells of %.3f m from (%.2f, %.2f) turned %.3f rad", g.width, g.height,
                  g.resolution, g.origin.x, g.origin.y, g.origin.theta);
  }
  return text;
}

MapObject read_object(const ConfigReader& entry, const std::vector<SemanticClass>& classes, const SemanticMap& map) {
  MapObject object;
  entry.read("name", &object.name);
  const std::string who = object.name.empty() ? "" : "object '" + object.name + "': ";
  entry.require("class");
  entry.read("class", &object.class_name);
  if (std::none_of(classes.begin(), classes.end(),
                   [&](const SemanticClass& c) { return c.name == object.class_name; })) {
    entry.fail("class", who + "unknown class '" + object.class_name + "' (the classes: " + class_names(classes) +
                            "; add others under 'classes:')");
  }
  const bool line = entry.has("line");
  if (line == entry.has("polygon")) {
    entry.fail(line ? "polygon" : "line", who + (line ? "give either line or polygon, not both"
                                                      : "missing: give line or polygon (x0, y0, x1, y1, ...)"));
  }
  object.shape = line ? ObjectShape::kLine : ObjectShape::kPolygon;
  const char* key = line ? "line" : "polygon";
  std::vector<double> flat;
  entry.read(key, &flat);
  const std::size_t needed = line ? 2 : 3;
  if (flat.size() % 2 != 0) {
    entry.fail(key, who + std::to_string(flat.size()) + " numbers are not x, y pairs (x0, y0, x1, y1, ...)");
  }
  if (flat.size() / 2 < needed) {
    entry.fail(key, who + (line ? "a line needs at least 2 points" : "a polygon needs at least 3 points") + ", got " +
                        std::to_string(flat.size() / 2));
  }
  for (std::size_t i = 0; i < flat.size(); i += 2) {
    const Eigen::Vector2d p(flat[i], flat[i + 1]);
    if (!map.geometry.cell_at(p)) {
      char text[120];
      std::snprintf(text, sizeof text, "point %zu (%.3f, %.3f) is outside the map (", i / 2 + 1, p.x(), p.y());
      entry.fail(key, who + text + describe_extent(map.geometry) + ")");
    }
    object.points.push_back(p);
  }
  if (entry.has("thickness")) {
    double thickness = 0.0;
    entry.read("thickness", &thickness, in_range(1e-6, 100.0));
    object.thickness = thickness;
  }
  std::string occupancy = "keep";
  entry.read_choice("occupancy", &occupancy, {"keep", "occupied", "free"});
  object.occupancy = occupancy == "occupied" ? CellOccupancy::kOccupied
                     : occupancy == "free"   ? CellOccupancy::kFree
                                             : CellOccupancy::kKeep;
  if (object_cells(object, map.geometry).empty()) {
    entry.fail(key, who + "covers no cell (a polygon smaller than a cell, or with its points on one line?)");
  }
  return object;
}

}  // namespace

std::vector<SemanticClass> project_classes() {
  return {{"door", {255, 0, 255}},
          {"glass_door", {0, 255, 255}},
          {"fence", {255, 128, 0}},
          {"no_entry_line", {255, 0, 0}},
          {"others", {0, 0, 0}}};
}

ObjectList read_object_list(const ConfigReader& reader, const SemanticMap& map) {
  ObjectList list;
  list.classes = read_classes(reader, map);
  reader.require("objects");
  for (const ConfigReader& entry : reader.list("objects")) {
    list.objects.push_back(read_object(entry, list.classes, map));
  }
  return list;
}

ObjectList load_object_list(const std::string& path, const SemanticMap& map) {
  const ConfigReader reader = ConfigReader::from_file(path);
  ObjectList list = read_object_list(reader, map);
  reader.check_all_keys_used();
  return list;
}

}  // namespace slamer

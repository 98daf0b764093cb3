#include "tools/datasets/wean_map.hpp"

#include <cmath>
#include <stdexcept>

#include "tools/datasets/dataset_lines.hpp"
#include "tools/datasets/tokens.hpp"

namespace slamer {

GridCells read_wean_map(const std::string& path) {
  DatasetLineReader reader(path);
  const auto fail = [&](const std::string& reason) {
    return std::runtime_error(path + ":" + std::to_string(reader.line_number()) + ": " + reason);
  };
  GridCells map;
  map.geometry.resolution = 0.1;
  double size_x_cm = 0.0;  // robot_specifications->global_mapsize_x and _y, when given: 0 if not
  double size_y_cm = 0.0;
  std::string line;
  while (true) {
    if (!reader.next(&line)) {
      throw fail("no 'global_map[0]: SIZE_Y SIZE_X' line");
    }
    dataset_detail::Tokens tokens(line);
    std::string_view key;
    if (!tokens.next(&key)) {
      continue;
    }
    if (key == "robot_specifications->resolution") {
      double centimetres = 0.0;
      if (!tokens.number(&centimetres) || !(centimetres > 0.0) || centimetres > 1000.0) {
        throw fail("bad resolution");
      }
      map.geometry.resolution = centimetres * 0.01;
    } else if (key == "robot_specifications->global_mapsize_x" || key == "robot_specifications->global_mapsize_y") {
      double& size = key.back() == 'x' ? size_x_cm : size_y_cm;
      if (!tokens.number(&size) || !(size > 0.0) || size > 1e7) {
        throw fail("bad " + std::string(key.substr(key.find('>') + 1)));
      }
    } else if (key == "global_map[0]:") {
      if (!tokens.number(&map.geometry.height) || !tokens.number(&map.geometry.width) || map.geometry.width <= 0 ||
          map.geometry.height <= 0 || map.geometry.width > 20000 || map.geometry.height > 20000) {
        throw fail("bad map size");
      }
      // The sizes in cm, where given, say which of the two numbers is which.
      const auto differs = [&](double cm, int cells) {
        return cm > 0.0 && !(std::abs(cm / (map.geometry.resolution * 100.0) - cells) < 0.5);
      };
      if (differs(size_x_cm, map.geometry.width) || differs(size_y_cm, map.geometry.height)) {
        throw fail("global_map[0] says " + std::to_string(map.geometry.height) + " (y) x " +
                   std::to_string(map.geometry.width) + " (x) cells; global_mapsize_x and _y say otherwise");
      }
      break;
    }
  }
  map.cells.assign(map.geometry.size(), Occupancy::kUnknown);
  for (int x = 0; x < map.geometry.width; ++x) {
    if (!reader.next(&line)) {
      throw fail("the file ends after " + std::to_string(x) + " of " + std::to_string(map.geometry.width) + " lines");
    }
    dataset_detail::Tokens tokens(line);
    for (int y = 0; y < map.geometry.height; ++y) {
      double free = 0.0;
      if (!tokens.number(&free) || !std::isfinite(free) || free > 1.0 || (free < 0.0 && free != -1.0)) {
        throw fail("cell " + std::to_string(y) + " is not a probability or -1");
      }
      Occupancy& cell = map.cells[map.geometry.index(x, y)];
      if (free >= 0.0 && free <= 0.35) {
        cell = Occupancy::kOccupied;
      } else if (free >= 0.804) {
        cell = Occupancy::kFree;
      }
    }
  }
  return map;
}

}  // namespace slamer

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
  std::string line;
  while (true) {
    if (!reader.next(&line)) {
      throw fail("no 'global_map[0]: W H' line");
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
    } else if (key == "global_map[0]:") {
      if (!tokens.number(&map.geometry.height) || !tokens.number(&map.geometry.width) || map.geometry.width <= 0 ||
          map.geometry.height <= 0 || map.geometry.width > 20000 || map.geometry.height > 20000) {
        throw fail("bad map size");
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

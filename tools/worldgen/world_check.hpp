// Checks a world the way issue 11 asks of a generated one: every region the
// route reaches is closed (with every door shut, no cell of it touches the
// map's unknown outside or its border), and the route (start, then each
// go_to in turn) keeps `clearance` from everything the truth has there at any
// time, except doors that are open throughout (and no-entry lines count as
// closed). Returns one line per problem; empty when the world is valid.
#pragma once

#include <string>
#include <vector>

namespace slamer {

struct WorldCheckResult {
  std::vector<std::string> problems;
  double route_length = 0.0;  // [m]
  std::size_t reachable_cells = 0;
};

WorldCheckResult check_world(const std::string& world_file, double clearance = 0.2);

}  // namespace slamer

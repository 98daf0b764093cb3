// slamer-gen-world: a random semantic building (map, truth, route) for slamer-sim and slamer-eval.
#include <iostream>

#include "common/process/process_main.hpp"
#include "tools/worldgen/world_check.hpp"
#include "tools/worldgen/world_files.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-gen-world",
      "Generates a random building into OUT_DIR, the same bytes for the same seed: the semantic map the\n"
      "robot is given (map.yaml, map.pgm, semantic.png, from plan.yaml), world.yaml for slamer-sim\n"
      "--world (route, materials with transmission and reflectance, a truth that differs from the map:\n"
      "doors opened, closed or changing during the run, objects added and removed), differences.yaml\n"
      "listing those differences, and robot.yaml. The world is checked (closed rooms, a route clear\n"
      "of every closed object) before it is written; --config takes the generator's options.",
      [](slamer::CommandLine& cli) {
        cli.add_option("seed", "N", "random seed", "1");
        cli.add_option("out", "DIR", "output folder");
        cli.add_option("robot", "FILE", "robot file copied into the world", SLAMER_DEFAULT_ROBOT);
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("out")) {
          throw slamer::CommandLineError("--out DIR is required");
        }
        const int64_t seed = cli.get_int("seed");
        if (seed < 0) {
          throw slamer::CommandLineError("--seed must be >= 0");
        }
        const auto options = slamer::load_config<slamer::WorldGenOptions>(cli);
        const slamer::Building building = slamer::generate_building(options, static_cast<uint64_t>(seed));
        const std::string dir = cli.get("out");
        slamer::write_world(building, options, static_cast<uint64_t>(seed), cli.get("robot"), dir);
        const slamer::WorldCheckResult check = slamer::check_world(dir + "/world.yaml");
        for (const std::string& problem : check.problems) {
          std::cerr << "slamer-gen-world: seed " << seed << ": " << problem << "\n";
        }
        return check.problems.empty() ? 0 : 1;
      });
}

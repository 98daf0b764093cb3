// slamer-make-map: renders a floor plan into a semantic map (PGM + PNG + YAML).
#include "common/process/process_main.hpp"
#include "tools/sim/floor_plan.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-make-map",
      "Renders a floor plan (plan.yaml: classes and thick polylines) into map.pgm, semantic.png and\n"
      "map.yaml in OUT_DIR, the semantic map format the stack loads.",
      [](slamer::CommandLine& cli) { cli.set_positional("PLAN OUT_DIR", "plan file and output folder", 2, 2); },
      [](const slamer::CommandLine& cli) {
        const auto plan = slamer::load_options<slamer::FloorPlan>(cli.positional()[0]);
        slamer::write_floor_plan_map(plan, cli.positional()[1]);
        return 0;
      });
}

// slamer-eval: scores logs against the simulation's ground truth (the paper's table).
#include <filesystem>
#include <iostream>

#include "common/process/process_main.hpp"
#include "tools/eval/eval_config.hpp"
#include "tools/eval/report.hpp"
#include "tools/eval/run_log.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-eval",
      "Scores logs of a simulated run against its ground truth, as in the paper's table: position and\n"
      "heading error Ave/Std/Max, time lost, and recognition accuracy Ave/Std/Min/Max of the recognizer\n"
      "alone, the simple map-based method and SLAMER. Several logs are shown side by side.",
      [](slamer::CommandLine& cli) {
        cli.add_option("world", "FILE", "the world file the logs were simulated in");
        cli.add_option("estimate", "CHANNEL", "channel of the estimate: POSE, GROUND_TRUTH or ODOMETRY", "POSE");
        cli.add_option("plot", "FILE.png", "also draw the position error over time");
        cli.add_flag("json", "print JSON instead of the table");
        cli.set_positional("LOG", "LCM logs to score", 1, 32);
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("world")) {
          throw slamer::CommandLineError("--world FILE is required");
        }
        const auto config = slamer::load_config<slamer::EvalConfig>(cli);
        const std::string world_file = cli.get("world");
        const auto world_options = slamer::load_options<slamer::WorldOptions>(world_file);
        const auto robot = slamer::load_options<slamer::RobotOptions>(world_options.robot_path);
        const slamer::SemanticMap map = slamer::load_semantic_map(world_options.map_path);
        const slamer::TrueWorld truth_world(map, world_options, world_file);
        slamer::WorldOptions as_mapped = world_options;
        as_mapped.doors.clear();
        as_mapped.objects.clear();
        as_mapped.removed.clear();
        const slamer::TrueWorld map_world(map, as_mapped, world_file);

        std::vector<slamer::NamedRun> runs;
        for (const std::string& path : cli.positional()) {
          const slamer::RunInputs inputs = slamer::read_run(path, config.channels, cli.get("estimate"));
          runs.push_back({std::filesystem::path(path).filename().string(),
                          slamer::score_run(inputs, truth_world, map_world, robot.lidar.mount, config.eval)});
        }
        std::cout << (cli.has("json") ? slamer::render_json(runs, config.eval)
                                      : slamer::render_table(runs, config.eval));
        if (cli.has("plot")) {
          slamer::write_error_plot(runs, cli.get("plot"));
        }
        return 0;
      });
}

#include "tools/eval_suite/suite_pipeline.hpp"

#include <filesystem>
#include <future>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "tools/datasets/run_program.hpp"
#include "tools/eval/run_log.hpp"

namespace slamer {
namespace {

void run(const SuiteSetup& setup, const std::string& program, const std::vector<std::string>& args) {
  const ProgramRun result = run_program(setup.bin_dir + "/" + program, args);
  if (result.exit_code != 0) {
    std::string line = program;
    for (const std::string& a : args) {
      line += " " + a;
    }
    throw std::runtime_error(line + " exited with " + std::to_string(result.exit_code));
  }
}

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

// The world, the simulation, the recognizer and the three localizers; returns the world's options.
WorldOptions run_programs(const SuiteSetup& setup, uint64_t seed, const std::string& directory,
                          const std::vector<std::string>& modes) {
  const auto [world_file, sim_log] = simulate_world(setup, seed, directory);
  const std::string recognized = directory + "/recognized.lcm";
  run(setup, "slamer-recognizer", {"--config", setup.recognizer_config, "--replay", sim_log, "--out", recognized});
  const auto world = load_options<WorldOptions>(world_file);
  std::vector<std::future<void>> pending;
  for (int localizer_seed = 1; localizer_seed <= setup.localizer_seeds; ++localizer_seed) {
    for (const std::string& mode : modes) {
      if (static_cast<int>(pending.size()) >= std::max(1, setup.jobs)) {
        pending.front().get();
        pending.erase(pending.begin());
      }
      pending.push_back(std::async(std::launch::async, [&, mode, localizer_seed] {
        run(setup, "slamer-localizer",
            {"--config", setup.localizer_config, "--mode", mode, "--seed", std::to_string(localizer_seed), "--map",
             world.map_path, "--robot", world.robot_path, "--initial-pose", number(world.start.x),
             number(world.start.y), number(world.start.theta), "--replay", recognized, "--out",
             directory + "/" + localizer_log(mode, localizer_seed)});
      }));
    }
  }
  for (std::future<void>& f : pending) {
    f.get();
  }
  return world;
}

}  // namespace

std::pair<std::string, std::string> simulate_world(const SuiteSetup& setup, uint64_t seed,
                                                   const std::string& directory) {
  std::vector<std::string> gen{"--seed", std::to_string(seed), "--out", directory + "/world"};
  if (!setup.gen_config.empty()) {
    gen.insert(gen.end(), {"--config", setup.gen_config});
  }
  run(setup, "slamer-gen-world", gen);
  const std::string world_file = directory + "/world/world.yaml";
  const std::string sim_log = directory + "/sim.lcm";
  run(setup, "slamer-sim",
      {"--world", world_file, "--config", setup.sim_config, "--seed", std::to_string(seed), "--out",
       sim_log + ".part"});
  std::filesystem::rename(sim_log + ".part", sim_log);
  return {world_file, sim_log};
}

std::string localizer_log(const std::string& mode, int localizer_seed) {
  return localizer_seed == 1 ? mode + ".lcm" : mode + "-s" + std::to_string(localizer_seed) + ".lcm";
}

std::vector<WorldResult> run_world(const SuiteSetup& setup, const EvalConfig& eval, uint64_t seed,
                                   const std::string& directory) {
  std::filesystem::create_directories(directory);
  const std::string world_file = directory + "/world/world.yaml";
  const std::vector<std::string> modes{"lfm", "slfm", "slamer"};
  bool have_logs = setup.reuse_logs;
  for (int localizer_seed = 1; localizer_seed <= setup.localizer_seeds; ++localizer_seed) {
    for (const std::string& mode : modes) {
      have_logs = have_logs && std::filesystem::exists(directory + "/" + localizer_log(mode, localizer_seed));
    }
  }
  const WorldOptions world =
      have_logs ? load_options<WorldOptions>(world_file) : run_programs(setup, seed, directory, modes);

  const auto differences = load_options<MapDifferences>(directory + "/world/differences.yaml");
  const auto robot = load_options<RobotOptions>(world.robot_path);
  const SemanticMap map = load_semantic_map(world.map_path);
  const TrueWorld truth(map, world, world_file);
  WorldOptions as_mapped = world;
  as_mapped.doors.clear();
  as_mapped.objects.clear();
  as_mapped.removed.clear();
  const TrueWorld mapped(map, as_mapped, world_file);
  std::vector<WorldResult> results;
  for (int localizer_seed = 1; localizer_seed <= setup.localizer_seeds; ++localizer_seed) {
    WorldResult& result = results.emplace_back();
    result.seed = seed;
    result.localizer_seed = localizer_seed;
    result.differences = differences;
    for (const std::string& mode : modes) {
      const std::string name = localizer_log(mode, localizer_seed);
      const std::string log = directory + "/" + name;
      const RunInputs inputs = read_run(log, eval.channels, eval.channels.pose);
      result.runs.push_back({name, score_run(inputs, truth, mapped, robot.lidar.mount, eval.eval)});
      if (mode == "slamer") {
        result.doors = score_differing_doors(inputs, truth, mapped, robot.lidar.mount, eval.eval, differences, false);
        result.changing_doors =
            score_differing_doors(inputs, truth, mapped, robot.lidar.mount, eval.eval, differences, true);
      }
      if (!setup.keep_logs) {
        std::filesystem::remove(log);
      }
    }
  }
  if (!setup.keep_logs) {
    std::filesystem::remove(directory + "/sim.lcm");
    std::filesystem::remove(directory + "/recognized.lcm");
  }
  return results;
}

}  // namespace slamer

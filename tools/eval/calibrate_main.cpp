// slamer-calibrate-recognizer: fits the recognizer's class rules and the
// recognition model's temperature (recognizer_fit.hpp) to simulated runs: logs
// of a given world, or training worlds it generates and simulates itself
// (seeds 1000 S + 1 + k, below the test worlds' 100000). Prints the rules as
// YAML for config/recognizer.yaml and the Dirichlet parameters for
// config/localizer.yaml; accuracies go to stderr.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "tools/eval/recognizer_fit.hpp"
#include "tools/eval_suite/suite_pipeline.hpp"

namespace slamer {
namespace {

struct Group {
  std::string world;
  std::vector<std::string> logs;
};

// Training world `seed`: generated and simulated (realistic odometry) into
// dir/train_SEED, unless an earlier run left it there.
Group training_world(const CommandLine& cli, uint64_t seed, const std::string& dir) {
  const std::string out = dir + "/train_" + std::to_string(seed);
  Group group{out + "/world/world.yaml", {out + "/sim.lcm"}};
  if (!std::filesystem::exists(group.logs[0])) {
    SuiteSetup setup;
    setup.bin_dir = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
    setup.sim_config = cli.get("sim-config");
    setup.gen_config = cli.has("gen-config") ? cli.get("gen-config") : "";
    simulate_world(setup, seed, out);
  }
  return group;
}

std::vector<LabelledObject> joined(const std::vector<std::vector<LabelledObject>>& groups, std::size_t parity) {
  std::vector<LabelledObject> all;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (parity > 1 || g % 2 == parity) {
      all.insert(all.end(), groups[g].begin(), groups[g].end());
    }
  }
  return all;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-calibrate-recognizer",
      "Fits the recognizer's class rules to simulated logs (LIDAR + GROUND_TRUTH) of --world, and/or of\n"
      "--train-worlds N generated training worlds (seeds 1000 S + 1 ... 1000 S + N, simulated with\n"
      "--sim-config into --out), and the recognition model's temperature a1 - a2 on worlds the rules\n"
      "were not fitted on (two folds: even and odd worlds). Prints YAML for config/recognizer.yaml's\n"
      "rules and config/localizer.yaml's dirichlet_a1/a2; accuracies go to stderr.",
      [](slamer::CommandLine& cli) {
        const std::string config = SLAMER_SOURCE_CONFIG;
        cli.add_option("world", "FILE", "the world the LOGs were simulated in");
        cli.add_option("train-worlds", "N", "generated training worlds (at most 999)", "0");
        cli.add_option("seed", "S", "training seed (0..98)", "0");
        cli.add_option("out", "DIR", "folder for the training worlds (kept: a second run reuses them)",
                       "calibration_worlds");
        cli.add_option("gen-config", "FILE", "slamer-gen-world options (default: its own)");
        cli.add_option("sim-config", "FILE", "slamer-sim config for the training worlds", config + "/sim.yaml");
        cli.add_option("eval-config", "FILE", "class meanings (config/eval.yaml)");
        cli.add_option("prior", "A", "pseudo-count added to every class of a bin", "0.5");
        cli.add_option("min-probability", "P", "the localizer's floor on a probability", "0.001");
        cli.set_positional("LOG", "simulated logs of --world", 0, 32);
      },
      [](const slamer::CommandLine& cli) {
        const int64_t train = cli.get_int("train-worlds");
        const int64_t seed = cli.get_int("seed");
        if (train < 0 || train > 999 || seed < 0 || seed > 98) {
          throw slamer::CommandLineError("--train-worlds must be in 0..999 and --seed in 0..98");
        }
        if (cli.has("world") == cli.positional().empty()) {
          throw slamer::CommandLineError("--world FILE and its LOGs go together");
        }
        if (!cli.has("world") && train == 0) {
          throw slamer::CommandLineError("nothing to fit on: give --world FILE LOG... or --train-worlds N");
        }
        const auto config = slamer::load_config<slamer::RecognizerProcessConfig>(cli);
        slamer::EvalConfig eval;
        if (cli.has("eval-config")) {
          eval = slamer::load_options<slamer::EvalConfig>(cli.get("eval-config"));
        }
        std::vector<slamer::Group> groups;
        if (cli.has("world")) {
          groups.push_back({cli.get("world"), cli.positional()});
        }
        for (int64_t k = 0; k < train; ++k) {
          const auto world_seed = static_cast<uint64_t>(1000 * seed + 1 + k);
          std::cerr << "slamer-calibrate-recognizer: training world " << k + 1 << " of " << train << " (seed "
                    << world_seed << ")\n";
          groups.push_back(slamer::training_world(cli, world_seed, cli.get("out")));
        }
        std::vector<std::vector<slamer::LabelledObject>> objects;
        for (const slamer::Group& g : groups) {
          std::string problems;
          objects.push_back(slamer::labelled_objects(g.world, g.logs, config, eval, &problems));
          if (!problems.empty()) {
            slamer::log_line("slamer-calibrate-recognizer", slamer::LogLevel::kWarning, problems);
          }
        }
        const std::vector<std::string>& classes = config.recognizer.classes;
        const double prior = cli.get_double("prior");
        const std::vector<slamer::LabelledObject> all = slamer::joined(objects, 2);
        const slamer::FittedRules fitted = slamer::fit_rules(all, classes, prior);
        // The temperature from the other fold's rules; one world alone: on itself, said.
        std::vector<slamer::FittedRules> fold_rules;
        std::vector<std::vector<slamer::LabelledObject>> fold_objects;
        for (std::size_t parity = 0; parity < 2 && groups.size() > 1; ++parity) {
          fold_rules.push_back(slamer::fit_rules(slamer::joined(objects, 1 - parity), classes, prior));
          fold_objects.push_back(slamer::joined(objects, parity));
        }
        std::vector<slamer::HeldOut> held_out;
        for (std::size_t f = 0; f < fold_rules.size(); ++f) {
          held_out.push_back({&fold_rules[f], &fold_objects[f]});
        }
        if (held_out.empty()) {
          held_out.push_back({&fitted, &all});
        }
        const double temperature = slamer::fit_temperature(held_out, cli.get_double("min-probability"));
        int64_t right_before = 0;
        for (const slamer::LabelledObject& o : all) {
          right_before += o.right_before ? 1 : 0;
        }
        std::cout << slamer::rules_yaml(fitted, classes);
        std::printf("# config/localizer.yaml, localizer.slamer (a1 - a2 = %.2f, fitted on %s):\n", temperature,
                    groups.size() > 1 ? "worlds the rules were not fitted on" : "the same world: no held-out one");
        std::printf("    dirichlet_a1: %.2f\n    dirichlet_a2: 1.0\n", 1.0 + temperature);
        std::cout << slamer::training_prior_yaml(fitted, classes);
        const double n = static_cast<double>(std::max<std::size_t>(all.size(), 1));
        std::fprintf(stderr,
                     "objects: %zu in %zu worlds; most likely class right: %.1f %% with the given rules, %.1f %% "
                     "fitted\n",
                     all.size(), groups.size(), 100.0 * static_cast<double>(right_before) / n,
                     100.0 * static_cast<double>(fitted.right) / n);
        return 0;
      });
}

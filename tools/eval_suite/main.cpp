// slamer-eval-suite: the stack on N generated test worlds it was not tuned on (issue 11).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "common/process/process_main.hpp"
#include "tools/eval_suite/suite_pipeline.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-eval-suite",
      "Generates N test worlds (slamer-gen-world; world k of seed S has seed 100000 + 1000 S + k, disjoint\n"
      "from the training seeds 1-99999), simulates each (slamer-sim, the sim config's realistic odometry),\n"
      "recognizes (slamer-recognizer --replay), localizes in lfm, slfm and slamer modes (slamer-localizer\n"
      "--replay with seeds 1..K of --localizer-seeds, from the world's start) and prints the paper's table\n"
      "per world and localizer seed, one line per run with the mean and the worst, the per-class confusion\n"
      "matrices of the recognizer, the map-based method and SLAMER, and the accuracies where the map\n"
      "differs from the truth. --config is the eval config (config/eval.yaml). The text is also written\n"
      "to OUT/summary.txt.",
      [](slamer::CommandLine& cli) {
        const std::string config = SLAMER_SOURCE_CONFIG;
        cli.add_option("worlds", "N", "test worlds (at most 1000)", "5");
        cli.add_option("seed", "S", "suite seed", "1");
        cli.add_option("out", "DIR", "work folder (a subfolder per world)", "suite_output");
        cli.add_option("gen-config", "FILE", "slamer-gen-world options (default: its own)");
        cli.add_option("sim-config", "FILE", "slamer-sim config", config + "/sim.yaml");
        cli.add_option("recognizer-config", "FILE", "slamer-recognizer config", config + "/recognizer.yaml");
        cli.add_option("localizer-config", "FILE", "slamer-localizer config", config + "/localizer.yaml");
        cli.add_option("jobs", "J", "localizer runs at once", "2");
        cli.add_option("localizer-seeds", "K", "localizer runs per world and mode, seeds 1..K (logs MODE-sS.lcm)", "1");
        cli.add_flag("keep-logs", "keep every world's logs (about 300 MB per 100 s of route)");
        cli.add_flag("reuse-logs", "score the logs a --keep-logs run left in OUT instead of running again");
      },
      [](const slamer::CommandLine& cli) {
        const int64_t worlds = cli.get_int("worlds");
        const int64_t seed = cli.get_int("seed");
        const int64_t jobs = cli.get_int("jobs");
        const int64_t localizer_seeds = cli.get_int("localizer-seeds");
        if (worlds < 1 || worlds > 1000 || seed < 0 || seed > 1'000'000 || jobs < 1 || localizer_seeds < 1 ||
            localizer_seeds > 100) {
          throw slamer::CommandLineError(
              "--worlds must be in 1..1000, --seed in 0..1000000, --jobs >= 1, --localizer-seeds in 1..100");
        }
        auto eval = slamer::load_config<slamer::EvalConfig>(cli);
        slamer::SuiteSetup setup;
        setup.bin_dir = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
        setup.sim_config = cli.get("sim-config");
        setup.recognizer_config = cli.get("recognizer-config");
        setup.localizer_config = cli.get("localizer-config");
        setup.gen_config = cli.has("gen-config") ? cli.get("gen-config") : "";
        setup.jobs = static_cast<int>(jobs);
        setup.localizer_seeds = static_cast<int>(localizer_seeds);
        setup.keep_logs = cli.has("keep-logs") || cli.has("reuse-logs");
        setup.reuse_logs = cli.has("reuse-logs");
        const std::string out = cli.get("out");
        std::filesystem::create_directories(out);
        std::ofstream summary(out + "/summary.txt");
        std::vector<slamer::WorldResult> results;
        for (int k = 0; k < worlds; ++k) {
          const uint64_t world_seed = slamer::test_world_seed(static_cast<uint64_t>(seed), k);
          std::cerr << "slamer-eval-suite: world " << k + 1 << " of " << worlds << " (seed " << world_seed << ")\n";
          for (slamer::WorldResult& run :
               slamer::run_world(setup, eval, world_seed, out + "/world_" + std::to_string(world_seed))) {
            const std::string text = slamer::render_world(run, eval.eval);
            std::cout << text << std::flush;
            summary << text;
            results.push_back(std::move(run));
          }
        }
        const std::string text = slamer::render_summary(results, eval.eval);
        std::cout << text;
        summary << text;
        return summary ? 0 : 1;
      });
}

// slamer-settle: when a localizer's estimate settles, per output log (settling.hpp).
#include <cstdio>
#include <string>
#include <vector>

#include "common/process/process_main.hpp"
#include "tools/datasets/bench_files.hpp"
#include "tools/datasets/settling.hpp"

namespace {

// "which agree within 0.50 m: runs 1 and 2 from scan 152 (28.4 s); run 3 with none" (runs 1-based, as given).
void print_groups(const std::vector<slamer::AgreeingGroup>& groups, double within) {
  std::printf("which agree within %.2f m:", within);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const slamer::AgreeingGroup& group = groups[g];
    std::string names;
    for (std::size_t i = 0; i < group.runs.size(); ++i) {
      names += (i == 0 ? "" : i + 1 == group.runs.size() ? " and " : ", ") + std::to_string(group.runs[i] + 1);
    }
    std::printf("%s", g == 0 ? " " : "; ");
    if (group.runs.size() == 1) {
      std::printf("run %s with none", names.c_str());
    } else if (group.agreement.scan) {
      std::printf("runs %s from scan %lld (%.1f s)", names.c_str(), static_cast<long long>(*group.agreement.scan),
                  group.agreement.seconds);
    } else {
      std::printf("runs %s pairwise, never all together", names.c_str());
    }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-settle",
      "For each localizer output LOG: after how many scans and seconds its estimate settles (the first scan\n"
      "from which no pose jumps more than --max-jump and at least 90 % say OK), the fraction OK, and the\n"
      "last pose. For logs without a reference, e.g. the CMU Wean logs localized with slamer-localizer --global.\n"
      "Settled is not right: with --agree M and the runs of one log with other seeds, also from which scan\n"
      "(among those every run has a pose for) the runs' poses all stay within M of each other to the end, and\n"
      "where they never do, of three runs or more, which of them do.",
      [](slamer::CommandLine& cli) {
        cli.set_positional("LOG...", "localizer output logs", 1, 1000);
        cli.add_option("pose-channel", "NAME", "the localizer's pose channel", "POSE");
        cli.add_option("max-jump", "M", "largest step between two poses of a settled estimate [m]", "0.5");
        cli.add_option("agree", "M", "also: from which scan the LOGs (two or more) agree within M [m]");
      },
      [](const slamer::CommandLine& cli) {
        const double within = cli.has("agree") ? cli.get_double("agree") : 0.0;
        if (cli.has("agree") && !(within > 0.0 && cli.positional().size() >= 2)) {
          throw slamer::CommandLineError("--agree takes a distance > 0 [m] and two LOGs or more");
        }
        std::vector<std::vector<slamer::PoseReport>> runs;
        for (const std::string& log : cli.positional()) {
          runs.push_back(slamer::read_pose_reports(log, cli.get("pose-channel")));
          const slamer::Settling s = slamer::settling(runs.back(), cli.get_double("max-jump"));
          char settled[96] = "never settled";
          if (s.scan) {
            std::snprintf(settled, sizeof settled, "settled from scan %lld (%.1f s)", static_cast<long long>(*s.scan),
                          s.seconds);
          }
          std::printf("%s: %lld scans; %s; OK %.1f %%; ends at (%.2f, %.2f, %.3f)\n", log.c_str(),
                      static_cast<long long>(s.scans), settled, s.ok_fraction * 100, s.end.x, s.end.y, s.end.theta);
        }
        if (cli.has("agree")) {
          const slamer::Agreement a = slamer::agreement(runs, within);
          if (a.scan) {
            std::printf(
                "the %zu runs agree within %.2f m from scan %lld (%.1f s) of %lld; largest spread after: %.2f m\n",
                runs.size(), within, static_cast<long long>(*a.scan), a.seconds, static_cast<long long>(a.scans),
                a.spread_after);
          } else {
            std::printf("the %zu runs never agree within %.2f m to the end of %lld scans; spread at the end: %.2f m\n",
                        runs.size(), within, static_cast<long long>(a.scans), a.spread_at_end);
            if (runs.size() >= 3) {
              print_groups(slamer::agreeing_groups(runs, within), within);
            }
          }
        }
        return 0;
      });
}

// slamer-settle: when a localizer's estimate settles, per output log (settling.hpp).
#include <cstdio>
#include <string>

#include "common/process/process_main.hpp"
#include "tools/datasets/bench_files.hpp"
#include "tools/datasets/settling.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-settle",
      "For each localizer output LOG: after how many scans and seconds its estimate settles (the first scan\n"
      "from which no pose jumps more than --max-jump and at least 90 % say OK), the fraction OK, and the\n"
      "last pose. For logs without a reference, e.g. the CMU Wean logs localized with slamer-localizer --global.",
      [](slamer::CommandLine& cli) {
        cli.set_positional("LOG...", "localizer output logs", 1, 1000);
        cli.add_option("pose-channel", "NAME", "the localizer's pose channel", "POSE");
        cli.add_option("max-jump", "M", "largest step between two poses of a settled estimate [m]", "0.5");
      },
      [](const slamer::CommandLine& cli) {
        for (const std::string& log : cli.positional()) {
          const slamer::Settling s =
              slamer::settling(slamer::read_pose_reports(log, cli.get("pose-channel")), cli.get_double("max-jump"));
          char settled[96] = "never settled";
          if (s.scan) {
            std::snprintf(settled, sizeof settled, "settled from scan %lld (%.1f s)", static_cast<long long>(*s.scan),
                          s.seconds);
          }
          std::printf("%s: %lld scans; %s; OK %.1f %%; ends at (%.2f, %.2f, %.3f)\n", log.c_str(),
                      static_cast<long long>(s.scans), settled, s.ok_fraction * 100, s.end.x, s.end.y, s.end.theta);
        }
        return 0;
      });
}

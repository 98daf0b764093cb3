// slamer-carmen2lcm: a recorded dataset (CARMEN, CMU Wean Hall or Mines) to an LCM log.
#include <string>

#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "tools/datasets/dataset_lcm.hpp"

namespace {

slamer::DatasetFormat parse_format(const std::string& name) {
  if (name == "carmen") {
    return slamer::DatasetFormat::kCarmen;
  }
  if (name == "cmu") {
    return slamer::DatasetFormat::kCmu;
  }
  if (name == "mines") {
    return slamer::DatasetFormat::kMines;
  }
  throw slamer::CommandLineError("option '--format': expected carmen, cmu or mines, got '" + name + "'");
}

slamer::ImportOptions::Corrected parse_corrected(const std::string& name) {
  using C = slamer::ImportOptions::Corrected;
  if (name == "auto") {
    return C::kAuto;
  }
  if (name == "yes") {
    return C::kYes;
  }
  if (name == "no") {
    return C::kNo;
  }
  throw slamer::CommandLineError("option '--corrected': expected auto, yes or no, got '" + name + "'");
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-carmen2lcm",
      "Converts a recorded 2D laser dataset (plain or gzip) into an LCM log: LIDAR (no-return codes\n"
      "as +inf), ODOMETRY, WHEEL_ENCODERS (Mines) and GROUND_TRUTH (pose_estimate_t, covariance zero:\n"
      "the corrected poses of a *-corrected CARMEN log, GMapping's estimate, not ground truth).\n"
      "  carmen: FLASER / ROBOTLASER1 / ODOM lines. In *-corrected logs the ODOM lines are\n"
      "    re-anchored to the corrected pose after every scan; the raw odometry is rebuilt by\n"
      "    chaining the increments inv(first ODOM after scan k) (+) (last ODOM before scan k+1),\n"
      "    and every ODOM line in between becomes raw_k (+) inv(first ODOM after k) (+) ODOM.\n"
      "  cmu: O and L lines of the CMU 16-831 Wean Hall logs (cm); L lines' poses add odometry.\n"
      "  mines: the Mines / BreezySLAM exp1.dat (wheel ticks integrated into ODOMETRY, URG-04LX).\n"
      "Time: utime strictly increases; a scan keeps the log's time in sensor_utime. Corrected CARMEN:\n"
      "a scan takes the log's time when it is >= 1 ms after the previous scan, else previous + 100 ms\n"
      "(every scan, when that is so for most: such a log has no time base);\n"
      "the rebuilt odometry at a scan has the scan's utime, the poses between two scans are spread\n"
      "evenly between them. Other logs in file order: the line's time if later than the previous\n"
      "message's, else that + 1 ms. Every event's timestamp is its message's utime. Malformed lines\n"
      "are reported (FILE:LINE: reason, the first 10, then a count) and skipped.",
      [](slamer::CommandLine& cli) {
        cli.set_positional("IN OUT.lcm", "dataset file (.gz or plain) and the LCM log to write", 2, 2);
        cli.add_option("format", "F", "carmen, cmu or mines", "carmen");
        cli.add_option("corrected", "C", "carmen: auto (detect re-anchored ODOM), yes or no", "auto");
      },
      [](const slamer::CommandLine& cli) {
        slamer::ImportOptions options;
        options.format = parse_format(cli.get("format"));
        options.corrected = parse_corrected(cli.get("corrected"));
        const std::string in = cli.positional()[0];
        const std::string out = cli.positional()[1];
        const slamer::ImportedLog log = slamer::import_dataset(in, options);
        for (const std::string& error : log.errors) {
          slamer::log_line("slamer-carmen2lcm", slamer::LogLevel::kWarning, "malformed line skipped: " + error);
        }
        if (log.malformed > static_cast<int64_t>(log.errors.size())) {
          slamer::log_line("slamer-carmen2lcm", slamer::LogLevel::kWarning,
                           std::to_string(log.malformed) + " malformed lines in all (the first " +
                               std::to_string(log.errors.size()) + " shown)");
        }
        if (log.scans.empty()) {
          throw std::runtime_error("no scans in " + in + " (wrong --format?)");
        }
        slamer::write_dataset_lcm(log, out);
        slamer::log_line("slamer-carmen2lcm", slamer::LogLevel::kInfo, out + ": " + slamer::describe_import(log));
        return 0;
      });
}

// slamer-recognizer: LIDAR in, LINE_OBJECTS out, live or from a log
// (--replay IN --out OUT); the wiring is recognizer_process.hpp's.
#include "common/process/process_main.hpp"
#include "recognizer/recognizer_process.hpp"

namespace slamer {
namespace {

int run(const CommandLine& cli) {
  const auto config = load_config<RecognizerProcessConfig>(cli);
  const std::unique_ptr<Bus> bus = open_bus(cli, "slamer-recognizer", config.process);
  const RecognizerProcess process(*bus, config);
  const int code = bus->run();
  bus->log_info(std::to_string(process.scans_recognized()) + " scans recognized, " +
                std::to_string(process.scans_missed()) + " missed (gaps in seq)");
  return code;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-recognizer",
      "Recognizes line objects (walls, doors, glass, fences as physical lines; open doorways and\n"
      "no-entry lines as spatial lines) with class probabilities in every LIDAR scan and publishes\n"
      "them on LINE_OBJECTS. With --replay IN --out OUT it reads a log instead, as fast as it can,\n"
      "copying every other channel through.",
      [](slamer::CommandLine& cli) { slamer::add_replay_options(cli, "LINE_OBJECTS"); }, slamer::run);
}

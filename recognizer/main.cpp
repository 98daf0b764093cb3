// slamer-recognizer: LIDAR in, LINE_OBJECTS out, live or from a log.
#include "common/process/convert.hpp"
#include "common/process/lcm_process.hpp"
#include "common/process/log.hpp"
#include "common/process/log_replay.hpp"
#include "common/process/stream_order.hpp"
#include "recognizer/line_recognizer.hpp"
#include "recognizer/recognizer_config.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"

namespace slamer {
namespace {

// Why a decoded scan cannot be used, or empty if it can.
std::string check_scan(const laser_scan_t& scan, int max_beams) {
  if (scan.nranges > max_beams) {
    return std::to_string(scan.nranges) + " beams (more than max_beams " + std::to_string(max_beams) + ")";
  }
  if (scan.nintensities != 0 && scan.nintensities != scan.nranges) {
    return "intensities do not match the ranges";
  }
  return "";
}

// Keeps track of the scan sequence: out-of-order or repeated scans are dropped;
// gaps in seq are scans lost before they reached us.
// Drops stale scans (stream_order.hpp) and counts the ones the sequence numbers say were missed.
struct ScanOrder {
  StreamOrder order;
  int64_t last_seq = -1;
  // Returns false for a scan to drop; adds missed scans to *missed.
  bool accept(const laser_scan_t& scan, int64_t* missed) {
    const Arrival arrival = order.check(scan.utime);
    if (arrival == Arrival::kStale) {
      return false;
    }
    if (arrival == Arrival::kInOrder && last_seq >= 0 && scan.seq > last_seq + 1) {
      *missed += scan.seq - last_seq - 1;
    }
    last_seq = scan.seq;
    return true;
  }
};

int run_live(const RecognizerProcessConfig& config, const std::string& lcm_url) {
  LcmProcess process("slamer-recognizer", lcm_url, config.process);
  const LineRecognizer recognizer(config.recognizer);
  ScanOrder order;
  int64_t last_scan_wall = now_utime();
  process.subscribe<laser_scan_t>(
      config.lidar_channel,
      [&](const laser_scan_t& scan, const ReceiveInfo&) {
        last_scan_wall = now_utime();
        if (const std::string problem = check_scan(scan, config.max_beams); !problem.empty()) {
          process.count_drop(config.lidar_channel);
          process.health().count_handler_error(config.lidar_channel + ": " + problem);
          return;
        }
        int64_t missed = 0;
        if (!order.accept(scan, &missed)) {
          process.count_drop(config.lidar_channel);
          return;
        }
        if (missed > 0) {
          process.count_drop(config.lidar_channel, missed);
        }
        process.publish(config.line_objects_channel,
                        to_line_objects_message(recognizer.recognize(from_message(scan)), scan.frame));
        if (process.health().state() != process_status_t::OK) {
          process.set_state(process_status_t::OK, "");
        }
      },
      true);
  process.every(1.0, [&] {
    if (now_utime() - last_scan_wall > 2'000'000) {
      process.set_state(process_status_t::DEGRADED, "no scans on " + config.lidar_channel + " for 2 s");
    }
  });
  return process.run();
}

int run_replay(const RecognizerProcessConfig& config, const std::string& in, const std::string& out) {
  const LineRecognizer recognizer(config.recognizer);
  ScanOrder order;
  int64_t bad = 0;
  int64_t dropped = 0;
  const ReplayStats stats = replay_log(
      "slamer-recognizer", in, out, {config.lidar_channel}, {config.line_objects_channel},
      [&](const std::string&, const std::vector<uint8_t>& bytes, int64_t, std::vector<OutputEvent>* outputs) {
        laser_scan_t scan{};
        int64_t missed = 0;
        if (decode_message(bytes.data(), bytes.size(), &scan) != DecodeStatus::kOk ||
            !check_scan(scan, config.max_beams).empty()) {
          ++bad;
          return;
        }
        if (!order.accept(scan, &missed)) {
          ++dropped;
          return;
        }
        outputs->push_back(encode_event(config.line_objects_channel,
                                        to_line_objects_message(recognizer.recognize(from_message(scan)), scan.frame)));
      });
  log_line("slamer-recognizer", LogLevel::kInfo,
           "replayed " + std::to_string(stats.events_handled) + " scans from " + in + " into " + out + " (" +
               std::to_string(bad) + " undecodable, " + std::to_string(dropped) + " out of order)");
  return 0;
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
      [](slamer::CommandLine& cli) {
        cli.add_option("replay", "IN.lcm", "offline: read scans from this log");
        cli.add_option("out", "OUT.lcm", "offline: write the log with LINE_OBJECTS added here");
      },
      [](const slamer::CommandLine& cli) {
        const auto config = slamer::load_config<slamer::RecognizerProcessConfig>(cli);
        if (cli.has("replay") != cli.has("out")) {
          throw slamer::CommandLineError("--replay and --out go together");
        }
        return cli.has("replay") ? slamer::run_replay(config, cli.get("replay"), cli.get("out"))
                                 : slamer::run_live(config, cli.get("lcm-url"));
      });
}

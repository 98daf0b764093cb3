// slamer-latency: the end-to-end latency and the losses of a live run, from
// the log lcm-logger recorded of it (latency_report.hpp).
#include <cstdio>
#include <iostream>

#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "tools/latency/latency_report.hpp"

namespace slamer {
namespace {

// First beam to last beam: the part of the latency the sensor's sweep takes.
double sweep_seconds(const laser_scan_t& scan) {
  return scan.nranges > 1 ? static_cast<double>(scan.time_increment) * (scan.nranges - 1) : 0.0;
}

int run(const CommandLine& cli) {
  EventLogReader log(cli.positional()[0]);
  LatencyRecorder recorder;
  int64_t undecodable = 0;
  const std::string lidar = cli.get("lidar"), objects = cli.get("objects"), pose = cli.get("pose"),
                    status = cli.get("status");
  while (const std::optional<LogEvent> e = log.next()) {
    const void* data = e->data.data();
    const std::size_t size = e->data.size();
    if (e->channel == lidar) {
      laser_scan_t m;
      if (decode_message(data, size, &m) == DecodeStatus::kOk) {
        recorder.on_scan(m.utime, m.seq, sweep_seconds(m), e->timestamp);
        continue;
      }
    } else if (e->channel == objects) {
      line_objects_t m;
      if (decode_message(data, size, &m) == DecodeStatus::kOk) {
        recorder.on_objects(m.utime, e->timestamp);
        continue;
      }
    } else if (e->channel == pose) {
      pose_estimate_t m;
      if (decode_message(data, size, &m) == DecodeStatus::kOk) {
        recorder.on_pose(m.utime, e->timestamp);
        continue;
      }
    } else if (e->channel == status) {
      process_status_t m;
      if (decode_message(data, size, &m) == DecodeStatus::kOk) {
        ProcessTotals t;
        t.messages_in = m.messages_in;
        t.messages_out = m.messages_out;
        t.decode_errors = m.decode_errors;
        t.drops = m.drops;
        t.processing_p99_ms = m.processing_time_p99 * 1e3;
        recorder.on_status(m.process, m.pid, t);
        continue;
      }
    } else {
      continue;
    }
    ++undecodable;
  }
  if (!log.problems().empty()) {
    log_line("slamer-latency", LogLevel::kWarning, log.problems());
  }
  if (undecodable > 0) {
    log_line("slamer-latency", LogLevel::kWarning, std::to_string(undecodable) + " messages did not decode, skipped");
  }
  const LatencyReport report = recorder.report();
  if (report.scans == 0) {
    log_line("slamer-latency", LogLevel::kError, "no " + lidar + " messages in " + cli.positional()[0]);
    return 1;
  }
  std::cout << (cli.has("json") ? render_json(report) : render_text(report));
  return 0;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-latency",
      "The end-to-end latency of a live run from the log lcm-logger recorded: per scan, from its first\n"
      "beam (the scan's utime) to its LIDAR, LINE_OBJECTS and POSE being on the bus (the logger's receive\n"
      "time), p50/p99/max; scans lost, scans without objects or pose; each process's last counters.",
      [](slamer::CommandLine& cli) {
        cli.add_option("lidar", "CHANNEL", "scans", "LIDAR");
        cli.add_option("objects", "CHANNEL", "the recognizer's output", "LINE_OBJECTS");
        cli.add_option("pose", "CHANNEL", "the localizer's output", "POSE");
        cli.add_option("status", "CHANNEL", "the processes' status", "PROCESS_STATUS");
        cli.add_flag("json", "print JSON instead of a table");
        cli.set_positional("LOG", "an LCM log recorded by lcm-logger during a live run", 1, 1);
      },
      [](const slamer::CommandLine& cli) { return slamer::run(cli); });
}

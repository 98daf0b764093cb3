#include "tools/datasets/dataset_lcm.hpp"

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

#include "common/process/convert.hpp"

namespace slamer {
namespace {

class Writer {
 public:
  explicit Writer(const std::string& path) : path_(path), file_(path, "w") {
    if (!file_.good()) {
      throw std::runtime_error("cannot write " + path);
    }
  }
  template <class Msg>
  void write(const std::string& channel, const Msg& msg, int64_t utime) {
    bytes_.resize(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes_.data(), 0, static_cast<int>(bytes_.size()));
    lcm::LogEvent event;
    event.timestamp = utime;
    event.channel = channel;
    event.datalen = static_cast<int32_t>(bytes_.size());
    event.data = bytes_.data();
    if (file_.writeEvent(&event) != 0) {
      throw std::runtime_error("cannot write to " + path_);
    }
  }

 private:
  std::string path_;
  lcm::LogFile file_;
  std::vector<uint8_t> bytes_;
};

}  // namespace

void write_dataset_lcm(const ImportedLog& log, const std::string& path, const DatasetChannels& channels) {
  Writer writer(path);
  for (const StreamEntry& e : merge_streams(log)) {
    switch (e.kind) {
      case StreamKind::kOdometry: {
        const TimedPose& p = log.odometry[e.index];
        writer.write(channels.odometry, make_odometry(p.utime, static_cast<int64_t>(e.index), p.pose, p.v, p.omega),
                     e.utime);
        break;
      }
      case StreamKind::kTicks: {
        const TickSample& t = log.ticks[e.index];
        writer.write(channels.wheel_encoders,
                     make_wheel_encoders(t.utime, static_cast<int64_t>(e.index), "dataset", t.left, t.right), e.utime);
        break;
      }
      case StreamKind::kScan:
        writer.write(channels.lidar, to_message(log.scans[e.index]), e.utime);
        break;
      case StreamKind::kGroundTruth:
        writer.write(channels.ground_truth, make_exact_pose(e.utime, log.reference[e.index]), e.utime);
        break;
    }
  }
}

std::string describe_import(const ImportedLog& log) {
  char text[400];
  std::snprintf(text, sizeof text,
                "%zu scans, %zu odometry poses%s, %zu encoder samples, %zu reference poses; %lld of %lld lines "
                "malformed; %lld retimed (log time not advancing)",
                log.scans.size(), log.odometry.size(), log.corrected ? " (raw, rebuilt from the re-anchored ODOM)" : "",
                log.ticks.size(), log.reference.size(), static_cast<long long>(log.malformed),
                static_cast<long long>(log.lines), static_cast<long long>(log.retimed));
  std::string line = text;
  if (log.laser_mount) {
    std::snprintf(text, sizeof text, "; laser mount (%.3f, %.3f, %.3f)", log.laser_mount->x, log.laser_mount->y,
                  log.laser_mount->theta);
    line += text;
  }
  if (log.corrected && (log.reanchor_mismatches > 0 || log.empty_intervals > 0)) {
    line += "; " + std::to_string(log.reanchor_mismatches) + " scans not re-anchored, " +
            std::to_string(log.empty_intervals) + " with no ODOM before the next (zero increment)";
  }
  return line;
}

}  // namespace slamer

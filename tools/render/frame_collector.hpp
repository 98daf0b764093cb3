// Frames from a log's messages, for slamer-render. A scan's pose, truth,
// particles and objects are published after the scan and carry its utime, so
// a kept scan (every `every`-th) becomes a frame only when the next scan
// arrives: by then everything for it is in. Messages that do not decode are
// skipped (a damaged log still draws).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tools/render/renderer.hpp"

namespace slamer {

class FrameCollector {
 public:
  explicit FrameCollector(int64_t every) : every_(every < 1 ? 1 : every) {}

  // One log event (channel, encoded message): the frames it completes, oldest first.
  std::vector<Frame> add(const std::string& channel, const std::vector<uint8_t>& data);
  // At the end of the log: the kept scans still waiting.
  std::vector<Frame> finish();

 private:
  Frame frame_of(const LaserScan& scan);
  std::vector<Frame> flush();

  int64_t every_;
  int64_t scan_count_ = 0;
  int64_t first_utime_ = -1;
  std::deque<LaserScan> scans_;
  // What arrived for recent scans, by the scan's utime.
  std::map<int64_t, Pose2> truth_;
  std::map<int64_t, Pose2> estimate_;
  std::map<int64_t, std::vector<Pose2>> particles_;
  std::map<int64_t, LineObjectSet> semantic_;
  std::map<int64_t, LineObjectSet> recognized_;
};

}  // namespace slamer

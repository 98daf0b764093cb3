#include "tools/render/frame_collector.hpp"

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/semantic_objects_t.hpp"

namespace slamer {

namespace {

// The value for `utime`, if any; everything up to it is done with.
template <class T>
std::optional<T> take(std::map<int64_t, T>& values, int64_t utime) {
  const auto it = values.find(utime);
  std::optional<T> value;
  if (it != values.end()) {
    value = it->second;
  }
  values.erase(values.begin(), values.upper_bound(utime));
  return value;
}

template <class Message>
std::optional<Message> decoded(const std::vector<uint8_t>& data) {
  Message m{};
  if (decode_message(data.data(), data.size(), &m) != DecodeStatus::kOk) {
    return std::nullopt;
  }
  return m;
}

}  // namespace

Frame FrameCollector::frame_of(const LaserScan& scan) {
  Frame frame;
  frame.utime = scan.utime;
  frame.elapsed = static_cast<double>(scan.utime - first_utime_) * 1e-6;
  frame.scan = scan;
  frame.truth = take(truth_, scan.utime);
  frame.estimate = take(estimate_, scan.utime);
  frame.particles = take(particles_, scan.utime).value_or(std::vector<Pose2>{});
  frame.semantic = take(semantic_, scan.utime);
  frame.recognized = take(recognized_, scan.utime);
  return frame;
}

std::vector<Frame> FrameCollector::flush() {
  std::vector<Frame> frames;
  for (; !scans_.empty(); scans_.pop_front()) {
    frames.push_back(frame_of(scans_.front()));
  }
  return frames;
}

std::vector<Frame> FrameCollector::add(const std::string& channel, const std::vector<uint8_t>& data) {
  if (channel == "LIDAR") {
    const auto m = decoded<laser_scan_t>(data);
    if (!m) {
      return {};
    }
    first_utime_ = first_utime_ < 0 ? m->utime : first_utime_;
    std::vector<Frame> frames = flush();
    if (scan_count_++ % every_ == 0) {
      scans_.push_back(from_message(*m));
    }
    return frames;
  }
  if (channel == "GROUND_TRUTH" || channel == "POSE") {
    if (const auto m = decoded<pose_estimate_t>(data)) {
      (channel == "POSE" ? estimate_ : truth_)[m->utime] = {m->x, m->y, m->theta};
    }
  } else if (channel == "PARTICLES") {
    if (const auto m = decoded<particles_t>(data)) {
      std::vector<Pose2>& list = particles_[m->utime];
      for (std::size_t i = 0; i < static_cast<std::size_t>(m->n); ++i) {
        list.push_back({m->x[i], m->y[i], m->theta[i]});
      }
    }
  } else if (channel == "SEMANTIC_OBJECTS") {
    if (const auto m = decoded<semantic_objects_t>(data)) {
      semantic_[m->utime] = from_message(*m);
    }
  } else if (channel == "LINE_OBJECTS") {
    if (const auto m = decoded<line_objects_t>(data)) {
      recognized_[m->utime] = from_message(*m);
    }
  }
  return {};
}

std::vector<Frame> FrameCollector::finish() {
  return flush();
}

}  // namespace slamer

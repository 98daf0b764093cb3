// libFuzzer target: the localizer node (filter included) on arbitrary input
// sequences on the small room map: scans, odometry, objects and initial poses
// built from the input bytes (NaN, infinities, huge values and times jumping
// both ways included), polled at arbitrary times. Whatever it is fed, every
// particle must stay finite and every published estimate must be a number.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "common/map/semantic_map.hpp"
#include "localizer/localizer_node.hpp"

namespace {

class Bytes {
 public:
  Bytes(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  template <class T>
  T take() {
    T value{};
    if (at_ < size_) {
      std::memcpy(&value, data_ + at_, std::min(sizeof(T), size_ - at_));  // zeros past the end
    }
    at_ += sizeof(T);
    return value;
  }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

// One node per mode, built once (the map's fields are the slow part); each input runs on a copy.
const slamer::LocalizerNode& fresh_node(int mode) {
  static const std::vector<slamer::LocalizerNode> nodes = [] {
    const slamer::SemanticMap map =
        slamer::load_semantic_map(std::string(SLAMER_SOURCE_DIR "/config/maps/small_room/map.yaml"));
    std::vector<slamer::LocalizerNode> built;
    for (int m = 0; m < 3; ++m) {
      slamer::LocalizerOptions options;
      options.particles = 40;
      options.initial_pose = {2.0, 3.0, 0.0};
      options.mode = static_cast<slamer::LocalizerMode>(m);
      built.emplace_back(map, options, slamer::Pose2{0.2, 0.0, 0.0});
    }
    return built;
  }();
  return nodes[static_cast<std::size_t>(mode)];
}

void check(bool ok) {
  if (!ok) {
    __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  slamer::LocalizerNode node = fresh_node(in.take<uint8_t>() % 3);
  int64_t utime = 1'000'000'000;
  for (int step = 0; step < 64 && !in.empty(); ++step) {
    utime += static_cast<int64_t>(in.take<int16_t>()) * 1000;  // jumps of up to 33 s either way
    switch (in.take<uint8_t>() % 5) {
      case 0: {
        slamer::LaserScan scan;
        scan.utime = utime;
        scan.angle_min = in.take<float>();
        scan.angle_increment = in.take<float>();
        scan.range_min = 0.05f;
        scan.range_max = in.take<float>();
        const int beams = in.take<uint8_t>();
        for (int i = 0; i < beams; ++i) {
          const uint16_t raw = in.take<uint16_t>();
          scan.ranges.push_back(raw == 0xffff   ? std::numeric_limits<float>::infinity()
                                : raw == 0xfffe ? std::numeric_limits<float>::quiet_NaN()
                                                : static_cast<float>(raw) * 0.0005f);
        }
        node.on_scan(scan);
        break;
      }
      case 1:
        node.on_odometry(utime, {in.take<float>(), in.take<float>(), in.take<float>()});
        break;
      case 2: {
        slamer::LineObjectSet set;
        set.utime = utime;
        set.class_names = {"open_door", "closed_door", "others", "free_space"};
        const int objects = in.take<uint8_t>() % 6;
        for (int i = 0; i < objects; ++i) {
          slamer::LineObject o;
          o.kind = in.take<uint8_t>() % 2 == 0 ? slamer::LineKind::kPhysical : slamer::LineKind::kSpatial;
          o.start = {in.take<float>(), in.take<float>()};
          o.end = {in.take<float>(), in.take<float>()};
          const int classes = in.take<uint8_t>() % 6;  // sometimes not one per class
          for (int c = 0; c < classes; ++c) {
            o.probs.push_back(in.take<float>());
          }
          set.objects.push_back(o);
        }
        node.on_objects(set);
        break;
      }
      case 3:
        node.on_initial_pose({in.take<float>(), in.take<float>(), in.take<float>()},
                             {in.take<float>(), in.take<float>(), in.take<float>()});
        break;
      case 4:
        while (const auto result = node.poll(utime)) {
          const slamer::Pose2& pose = result->estimate.pose;
          check(std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta));
        }
        break;
    }
    for (const slamer::Particle& p : node.particles()) {
      check(std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.theta) &&
            !std::isnan(p.log_weight));
    }
  }
  return 0;
}

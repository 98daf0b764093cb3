// libFuzzer target: every dataset line parser (CARMEN FLASER / ROBOTLASER1 /
// ODOM, CMU O / L, Mines) on arbitrary text. First byte: the format.
#include <cmath>
#include <cstdint>
#include <string>

#include "tools/datasets/dataset_records.hpp"

namespace {

bool finite(const slamer::Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) {
    return 0;
  }
  const auto format = static_cast<slamer::DatasetFormat>(data[0] % 3);
  const std::string line(reinterpret_cast<const char*>(data + 1), size - 1);
  slamer::DatasetRecord record;
  std::string error;
  if (!slamer::parse_dataset_record(format, line, &record, &error)) {
    if (error.empty()) {
      __builtin_trap();  // a rejected line always says why
    }
    return 0;
  }
  if (record.kind == slamer::RecordKind::kScan) {
    for (const float r : record.scan.ranges) {
      if (std::isnan(r) || r < 0.0f) {
        __builtin_trap();  // distances or +inf, never NaN or negative
      }
    }
    if (record.scan.ranges.empty() || !(record.scan.angle_increment > 0.0) || record.scan.utime < 0 ||
        !finite(record.pose) || !finite(record.base_pose)) {
      __builtin_trap();
    }
  }
  if (record.kind == slamer::RecordKind::kOdometry && !finite(record.pose)) {
    __builtin_trap();
  }
  return 0;
}

// libFuzzer target: the dataset line parsers on arbitrary text.
#include <cmath>
#include <cstdint>
#include <string>

#include "tools/datasets/dataset_scans.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) {
    return 0;
  }
  const auto format = static_cast<slamer::DatasetFormat>(data[0] % 3);
  const std::string line(reinterpret_cast<const char*>(data + 1), size - 1);
  slamer::LaserScan scan;
  if (slamer::parse_dataset_line(format, line, &scan)) {
    for (const float r : scan.ranges) {
      if (std::isnan(r) || r < 0.0f) {
        __builtin_trap();  // parsed ranges are distances or +inf, never NaN or negative
      }
    }
  }
  return 0;
}

// libFuzzer target: the recognizer on arbitrary scans (ranges, angles and
// limits from the input bytes, NaN and infinities included). It must return
// objects whose probabilities sum to 1, whatever it is given.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "recognizer/line_recognizer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 16) {
    return 0;
  }
  slamer::LaserScan scan;
  float header[4];
  std::memcpy(header, data, sizeof(header));
  scan.angle_min = header[0];
  scan.angle_increment = header[1];
  scan.range_min = header[2];
  scan.range_max = header[3];
  const std::size_t beams = std::min<std::size_t>((size - 16) / 2, 4000);
  for (std::size_t i = 0; i < beams; ++i) {
    uint16_t raw = 0;
    std::memcpy(&raw, data + 16 + 2 * i, 2);
    // Mostly plausible ranges in [0, 32.7] m, with the special values mixed in.
    scan.ranges.push_back(raw == 0xffff   ? std::numeric_limits<float>::infinity()
                          : raw == 0xfffe ? std::numeric_limits<float>::quiet_NaN()
                          : raw == 0xfffd ? -std::numeric_limits<float>::infinity()
                                          : static_cast<float>(raw) * 0.0005f);
  }
  static const slamer::LineRecognizer recognizer{slamer::RecognizerOptions{}};
  const slamer::LineObjectSet result = recognizer.recognize(scan);
  for (const slamer::LineObject& o : result.objects) {
    double sum = 0.0;
    for (const float p : o.probs) {
      sum += p;
    }
    if (std::abs(sum - 1.0) > 1e-4 || !std::isfinite(o.start.x()) || !std::isfinite(o.end.y())) {
      __builtin_trap();
    }
  }
  return 0;
}

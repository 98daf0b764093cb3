// libFuzzer target: arbitrary sensor bytes through the framer, reply, key:value and scan parsers.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "drivers/urg/scip_scan.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace slamer::urg;
  ReplyFramer framer(4096);
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> lines;
  // Feed in two pieces so split points are exercised.
  framer.feed(bytes.substr(0, size / 2));
  for (int pass = 0; pass < 2; ++pass) {
    while (framer.next(&lines)) {
      const Reply reply = parse_reply(lines);
      (void)reply.kind();
      const KeyValues kv = parse_key_values(reply);
      SensorGeometry geometry;
      std::string error;
      if (parse_geometry(kv, &geometry, &error)) {
        (void)geometry.angle_of_step(geometry.amax);
      }
      ScanData scan;
      if (decode_scan(reply, &scan) == ScanError::kOk) {
        for (uint32_t v : scan.distances) {
          (void)range_from_device(v, geometry);
        }
      }
    }
    framer.feed(bytes.substr(size / 2));
  }
  return 0;
}

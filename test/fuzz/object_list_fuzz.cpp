// libFuzzer target: slamer-annotate-map's objects file (tools/annotate/object_list.hpp)
// with arbitrary bytes, read for a small map and painted. Any input gives
// an object list that paints, or a one-line ConfigError.
#include <cstdint>
#include <string>

#include "tools/annotate/annotate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const slamer::SemanticMap map = [] {
    slamer::SemanticMap m;
    m.geometry.width = 40;
    m.geometry.height = 30;
    m.geometry.resolution = 0.05;
    m.geometry.origin = {-0.5, -0.25, 0.1};
    m.occupancy.assign(m.geometry.size(), slamer::Occupancy::kFree);
    m.labels.assign(m.geometry.size(), -1);
    return m;
  }();
  try {
    const slamer::ConfigReader reader =
        slamer::ConfigReader::from_string(std::string(reinterpret_cast<const char*>(data), size), "objects.yaml");
    const slamer::ObjectList list = slamer::read_object_list(reader, map);
    reader.check_all_keys_used();
    const slamer::SemanticMap painted = slamer::annotate_map(map, list);
    if (painted.labels.size() != map.labels.size()) {
      __builtin_trap();
    }
  } catch (const slamer::ConfigError& e) {
    const std::string message = e.what();
    if (message.empty() || message.find('\n') != std::string::npos) {
      __builtin_trap();  // errors are one line
    }
  }
  return 0;
}

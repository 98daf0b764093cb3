// libFuzzer target: the strict YAML options loader on arbitrary text, as a
// process config and as the localizer's saved pose file (which a power cut or
// a full disk may leave as anything). Any input must give options or a
// one-line ConfigError, nothing else.
#include <cstdint>
#include <string>

#include "common/config/config_reader.hpp"
#include "localizer/saved_pose.hpp"
#include "tools/status/status_table.hpp"

namespace {

template <class Options>
void parse(const std::string& text) {
  try {
    slamer::parse_options<Options>(text, "fuzz.yaml");
  } catch (const slamer::ConfigError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) {
      __builtin_trap();  // errors must stay on one line
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  parse<slamer::StatusProcessConfig>(text);
  parse<slamer::SavedPose>(text);
  return 0;
}

// libFuzzer target: the strict YAML options loader on arbitrary text. Any
// input must give options or a one-line ConfigError, nothing else.
#include <cstdint>
#include <string>

#include "common/config/config_reader.hpp"
#include "tools/status/status_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    slamer::parse_options<slamer::StatusProcessConfig>(text, "fuzz.yaml");
  } catch (const slamer::ConfigError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) {
      __builtin_trap();  // errors must stay on one line
    }
  }
  return 0;
}

// libFuzzer target: loading a map whose image bytes are arbitrary (the first
// input byte picks PGM or PNG occupancy, or the semantic PNG layer). Any input
// gives a map or a one-line ConfigError.
#include <cstdint>
#include <fstream>
#include <string>

#include "common/map/semantic_map.hpp"
#include "test/support/temp_dir.hpp"

namespace {

const slamer::test::TempDir& directory() {
  static const slamer::test::TempDir dir("slamer_map_fuzz");
  return dir;
}

void write(const std::string& name, const uint8_t* data, std::size_t size) {
  std::ofstream(directory().file(name), std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) {
    return 0;
  }
  static const uint8_t kPgm[] = "P5\n4 3\n255\n\x00\xfe\xcd\x64\xfe\xfe\xfe\xfe\x00\x00\xfe\xa0";
  const int mode = data[0] % 3;
  const std::string occupancy = mode == 1 ? "map.png" : "map.pgm";
  if (mode == 2) {
    write("map.pgm", kPgm, sizeof(kPgm) - 1);
  }
  write(mode == 2 ? "semantic.png" : occupancy, data + 1, size - 1);
  const std::string yaml = directory().write(
      "map.yaml",
      "image: " + occupancy + "\nresolution: 0.05\norigin: [0, 0, 0]\n" +
          (mode == 2 ? "semantic:\n  image: semantic.png\n  classes: [{name: door, color: [255, 0, 255]}]\n" : ""));
  try {
    slamer::load_semantic_map(yaml);
  } catch (const slamer::ConfigError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) {
      __builtin_trap();
    }
  }
  return 0;
}

// libFuzzer: arbitrary text replies through the reply collector, VV and PP parsers.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "drivers/wheels/tfrog_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  slamer::tfrog::ReplyCollector collector("VV");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    collector.add_line(line);
    lines.push_back(line);
  }
  std::string error;
  (void)slamer::tfrog::parse_vv(lines, &error);
  (void)slamer::tfrog::parse_pp(lines, &error);
  (void)slamer::tfrog::parse_vv(collector.reply().body, &error);
  return 0;
}

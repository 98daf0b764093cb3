// libFuzzer target: the LCM log reader on arbitrary bytes (a damaged disk, a
// logger killed mid-write, a file that is no log at all). It must read every
// event it can, account for every other byte, and never crash or loop.
#include <cstdint>
#include <cstdio>

#include "common/process/event_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  slamer::EventLogReader reader(fmemopen(const_cast<uint8_t*>(data), size, "rb"), "fuzz.lcm");
  std::size_t event_bytes = 0;
  while (const auto event = reader.next()) {
    event_bytes += slamer::kLogEventHeaderBytes + event->channel.size() + event->data.size();
  }
  if (event_bytes + static_cast<std::size_t>(reader.damaged_bytes()) != size) {
    __builtin_trap();  // every byte is either in an event or counted as damaged
  }
  if (reader.problems().find('\n') != std::string::npos) {
    __builtin_trap();
  }
  return 0;
}

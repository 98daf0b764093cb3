// libFuzzer: arbitrary board bytes through the splitter and the frame decoders.
#include <cstddef>
#include <cstdint>
#include <span>

#include "drivers/wheels/tfrog_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  slamer::tfrog::StreamSplitter splitter(64);
  std::vector<slamer::tfrog::StreamItem> items;
  const std::span<const uint8_t> bytes(data, size);
  splitter.feed(bytes.first(size / 2), &items);
  splitter.feed(bytes.subspan(size / 2), &items);
  for (const auto& item : items) {
    (void)slamer::tfrog::decode_odometry(item.raw, 2, 0);
    (void)slamer::tfrog::decode_odometry(item.raw, 2, 1);
    (void)slamer::tfrog::decode_interrupt(item.raw);
    (void)slamer::tfrog::parse_command_record(item.raw);
  }
  (void)slamer::tfrog::decode_payload(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}

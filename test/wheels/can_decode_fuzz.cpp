// libFuzzer: arbitrary bytes as can_frames through the decoder, and as candump log lines.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "drivers/wheels/can_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  slamer::can::CanLayout layout;
  layout.wheels[0].id = 0x101;
  layout.wheels[1].id = 0x102;
  layout.wheels[1].velocity = true;
  slamer::can::CanDecoder decoder(layout);
  slamer::can::CanDecoder canopen(slamer::can::CanLayout{.preset = "canopen"});
  const std::span<const uint8_t> bytes(data, size);
  for (std::size_t at = 0; at + 16 <= size; at += 16) {
    if (auto frame = slamer::can::parse_can_frame(bytes.subspan(at, 16))) {
      frame->utime = static_cast<int64_t>(at) * 1000;
      (void)decoder.feed(*frame);
      (void)canopen.feed(*frame);
    }
  }
  std::string error;
  (void)slamer::can::parse_candump_line(std::string(reinterpret_cast<const char*>(data), size), &error);
  return 0;
}

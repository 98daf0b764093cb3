// libFuzzer target: every message type's decoder on arbitrary bytes. The first
// byte picks the type; the rest is fed with that type's fingerprint in front
// half of the time, so the fuzzer reaches the field decoders.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "common/process/decode.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "slamer/semantic_objects_t.hpp"
#include "slamer/velocity_command_t.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace {

template <class Msg>
void fuzz_one(const uint8_t* data, std::size_t size, bool add_fingerprint) {
  std::vector<uint8_t> bytes;
  if (add_fingerprint) {
    bytes.resize(8);
    const int64_t hash = Msg::getHash();
    __int64_t_encode_array(bytes.data(), 0, 8, &hash, 1);
  }
  bytes.insert(bytes.end(), data, data + size);
  Msg msg;
  if (slamer::decode_message(bytes.data(), bytes.size(), &msg) == slamer::DecodeStatus::kOk) {
    // Whatever decodes must encode back to the same bytes.
    std::vector<uint8_t> again(static_cast<std::size_t>(msg.getEncodedSize()));
    if (msg.encode(again.data(), 0, static_cast<int>(again.size())) != static_cast<int>(again.size()) ||
        again != bytes) {
      std::fprintf(stderr, "MISMATCH size %zu vs %zu\n", bytes.size(), again.size());
      for (std::size_t i = 0; i < std::max(bytes.size(), again.size()); ++i) {
        std::fprintf(stderr, "%02x/%02x ", i < bytes.size() ? bytes[i] : 0, i < again.size() ? again[i] : 0);
      }
      std::fprintf(stderr, "\n");
      __builtin_trap();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1) {
    return 0;
  }
  const bool add_fingerprint = (data[0] & 0x80) != 0;
  const uint8_t type = data[0] & 0x7f;
  data += 1;
  size -= 1;
  switch (type % 10) {
    case 0:
      fuzz_one<slamer::laser_scan_t>(data, size, add_fingerprint);
      break;
    case 1:
      fuzz_one<slamer::wheel_encoders_t>(data, size, add_fingerprint);
      break;
    case 2:
      fuzz_one<slamer::odometry_t>(data, size, add_fingerprint);
      break;
    case 3:
      fuzz_one<slamer::line_objects_t>(data, size, add_fingerprint);
      break;
    case 4:
      fuzz_one<slamer::pose_estimate_t>(data, size, add_fingerprint);
      break;
    case 5:
      fuzz_one<slamer::semantic_objects_t>(data, size, add_fingerprint);
      break;
    case 6:
      fuzz_one<slamer::particles_t>(data, size, add_fingerprint);
      break;
    case 7:
      fuzz_one<slamer::velocity_command_t>(data, size, add_fingerprint);
      break;
    case 8:
      fuzz_one<slamer::initial_pose_t>(data, size, add_fingerprint);
      break;
    default:
      fuzz_one<slamer::process_status_t>(data, size, add_fingerprint);
      break;
  }
  return 0;
}

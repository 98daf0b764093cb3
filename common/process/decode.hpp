// Decoding LCM messages from untrusted bytes, with the reason for a failure.
//
// Any process may receive anything on a channel (another program publishing a
// different type, a truncated UDP datagram, garbage), so decoding never
// throws and never trusts a length field: the generated decoders are
// hardened at build time (cmake/harden_lcm_decoders.cmake) and whatever they
// still throw is caught here.
#pragma once

#include <lcm/lcm_coretypes.h>

#include <climits>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

namespace slamer {

enum class DecodeStatus {
  kOk,
  kTooShort,          // fewer than the 8 fingerprint bytes
  kWrongFingerprint,  // a different message type (or garbage)
  kMalformed,         // right type, but truncated or with impossible lengths
  kTrailingBytes,     // right type, decoded, but bytes left over
};

std::string_view describe(DecodeStatus status);

template <class Msg>
DecodeStatus decode_message(const void* data, std::size_t size, Msg* msg) {
  if (size < 8) {
    return DecodeStatus::kTooShort;
  }
  if (size > static_cast<std::size_t>(INT_MAX)) {
    return DecodeStatus::kMalformed;
  }
  int64_t fingerprint = 0;
  if (__int64_t_decode_array(data, 0, 8, &fingerprint, 1) != 8 || fingerprint != Msg::getHash()) {
    return DecodeStatus::kWrongFingerprint;
  }
  int used = -1;
  try {
    used = msg->decode(data, 0, static_cast<int>(size));
  } catch (const std::exception&) {
    return DecodeStatus::kMalformed;
  }
  if (used < 0) {
    return DecodeStatus::kMalformed;
  }
  return static_cast<std::size_t>(used) == size ? DecodeStatus::kOk : DecodeStatus::kTrailingBytes;
}

}  // namespace slamer

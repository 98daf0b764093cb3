#include "common/process/decode.hpp"

namespace slamer {

std::string_view describe(DecodeStatus status) {
  switch (status) {
    case DecodeStatus::kOk:
      return "ok";
    case DecodeStatus::kTooShort:
      return "shorter than a fingerprint";
    case DecodeStatus::kWrongFingerprint:
      return "wrong fingerprint";
    case DecodeStatus::kMalformed:
      return "truncated or malformed";
    case DecodeStatus::kTrailingBytes:
      return "trailing bytes";
  }
  return "unknown";
}

}  // namespace slamer

#include "drivers/urg/scip_codec.hpp"

#include <cstdio>

namespace slamer::urg {

char scip_checksum(std::string_view bytes) {
  unsigned sum = 0;
  for (const char c : bytes) {
    sum += static_cast<unsigned char>(c);
  }
  return static_cast<char>((sum & 0x3Fu) + 0x30u);
}

bool line_checksum_ok(std::string_view line) {
  if (line.empty()) {
    return false;
  }
  const char sum = line.back();
  const std::string_view body = line.substr(0, line.size() - 1);
  if (scip_checksum(body) == sum) {
    return true;
  }
  if (!body.empty() && body.back() == ';' && scip_checksum(body.substr(0, body.size() - 1)) == sum) {
    return true;
  }
  const std::size_t arrow = body.find("<-");
  if (arrow != std::string_view::npos) {
    if (scip_checksum(body.substr(0, arrow)) == sum || scip_checksum(body.substr(0, arrow + 2)) == sum) {
      return true;
    }
  }
  return false;
}

std::string scip_encode(uint64_t value, int chars) {
  std::string out(static_cast<std::size_t>(chars), '0');
  for (int i = chars - 1; i >= 0; --i) {
    out[static_cast<std::size_t>(i)] = static_cast<char>((value & 0x3Fu) + 0x30u);
    value >>= 6;
  }
  return out;
}

std::optional<uint64_t> scip_decode(std::string_view chars) {
  if (chars.empty() || chars.size() > 10) {
    return std::nullopt;
  }
  uint64_t value = 0;
  for (const char c : chars) {
    const int v = static_cast<unsigned char>(c) - 0x30;
    if (v < 0 || v > 0x3F) {
      return std::nullopt;
    }
    value = (value << 6) | static_cast<uint64_t>(v);
  }
  return value;
}

std::string scip_command(std::string_view command, std::string_view tag) {
  std::string out(command);
  if (!tag.empty()) {
    out += ';';
    out += tag;
  }
  out += '\n';
  return out;
}

std::string scip_scan_command(bool intensity, int start, int end, int cluster, int skip, int scans,
                              std::string_view tag) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%s%04d%04d%02d%1d%02d", intensity ? "ME" : "MD", start, end, cluster, skip,
                scans);
  return scip_command(buffer, tag);
}

}  // namespace slamer::urg

#include "drivers/urg/scip_scan.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>

#include "drivers/urg/scip_codec.hpp"

namespace slamer::urg {

double SensorGeometry::angle_of_step(int step) const {
  return static_cast<double>(step - afrt) * angle_increment();
}
double SensorGeometry::angle_increment() const {
  return ares > 0 ? 2.0 * std::numbers::pi / ares : 0.0;
}
double SensorGeometry::scan_period() const {
  return scan_rpm > 0 ? 60.0 / scan_rpm : 0.0;
}
double SensorGeometry::time_increment() const {
  return ares > 0 ? scan_period() / ares : 0.0;
}

namespace {

bool to_int(const std::string& text, int* value) {
  // PP values may carry a unit comment after a space ("SCAN:2400", "AMIN:0"); take the leading integer.
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  return ec == std::errc() && ptr != begin;
}

bool digits(const std::string& text, std::size_t pos, std::size_t count, int* value) {
  if (pos + count > text.size()) {
    return false;
  }
  int v = 0;
  for (std::size_t i = pos; i < pos + count; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) {
      return false;
    }
    v = v * 10 + (text[i] - '0');
  }
  *value = v;
  return true;
}

bool is_urg04_family(const std::string& model) {
  return model.find("URG-04") != std::string::npos || model.find("UBG-04") != std::string::npos ||
         model.find("UHG-08") != std::string::npos || model.find("URG-X") != std::string::npos;
}

}  // namespace

bool parse_geometry(const KeyValues& pp, SensorGeometry* g, std::string* error) {
  struct Field {
    const char* key;
    int* value;
  };
  const Field fields[] = {{"DMIN", &g->dmin}, {"DMAX", &g->dmax}, {"ARES", &g->ares},    {"AMIN", &g->amin},
                          {"AMAX", &g->amax}, {"AFRT", &g->afrt}, {"SCAN", &g->scan_rpm}};
  for (const Field& field : fields) {
    const std::string* text = pp.find(field.key);
    if (text == nullptr || !to_int(*text, field.value)) {
      *error = std::string("PP reply has no valid ") + field.key;
      return false;
    }
  }
  if (const std::string* model = pp.find("MODL")) {
    g->model = *model;
  }
  if (g->ares <= 0 || g->amin < 0 || g->amax < g->amin || g->dmax <= g->dmin || g->dmin < 0 || g->scan_rpm <= 0) {
    *error = "PP reply has inconsistent values (ARES, AMIN..AMAX, DMIN..DMAX or SCAN)";
    return false;
  }
  return true;
}

const char* scan_error_name(ScanError error) {
  switch (error) {
    case ScanError::kOk:
      return "ok";
    case ScanError::kChecksum:
      return "checksum";
    case ScanError::kTruncated:
      return "truncated";
    case ScanError::kLength:
      return "length";
    case ScanError::kBadEcho:
      return "bad_echo";
    case ScanError::kBadChar:
      return "bad_char";
    case ScanError::kStatus:
      return "status";
  }
  return "?";
}

int ScanParams::expected_values() const {
  const int c = cluster < 1 ? 1 : cluster;
  return (end - start + 1 + c - 1) / c;
}

std::optional<ScanParams> parse_scan_echo(const std::string& echo) {
  const std::string head = echo.substr(0, echo.find(';'));
  if (head.size() < 12) {
    return std::nullopt;
  }
  ScanParams p;
  const std::string cmd = head.substr(0, 2);
  if (cmd == "MD" || cmd == "ME") {
    p.continuous = true;
  } else if (cmd != "GD" && cmd != "GE") {
    return std::nullopt;
  }
  p.intensity = cmd[1] == 'E';
  if (!digits(head, 2, 4, &p.start) || !digits(head, 6, 4, &p.end) || !digits(head, 10, 2, &p.cluster)) {
    return std::nullopt;
  }
  if (p.continuous) {
    if (head.size() != 15 || !digits(head, 12, 1, &p.skip) || !digits(head, 13, 2, &p.scans)) {
      return std::nullopt;
    }
  } else if (head.size() != 12) {
    return std::nullopt;
  }
  if (p.end < p.start) {
    return std::nullopt;
  }
  return p;
}

ScanError decode_scan(const Reply& reply, ScanData* scan) {
  const auto params = parse_scan_echo(reply.echo);
  if (!params) {
    return ScanError::kBadEcho;
  }
  scan->params = *params;
  scan->distances.clear();
  scan->intensities.clear();
  const StatusKind kind = reply.kind();
  if (kind != StatusKind::kScanData && !(kind == StatusKind::kOk && !params->continuous)) {
    return ScanError::kStatus;
  }
  if (!reply.status_checksum_ok || reply.bad_checksum_lines > 0) {
    return ScanError::kChecksum;
  }
  if (reply.lines.empty()) {
    return ScanError::kTruncated;
  }
  const std::string& stamp_line = reply.lines[0];
  if (stamp_line.size() != 5) {
    return ScanError::kLength;
  }
  const auto stamp = scip_decode(std::string_view(stamp_line).substr(0, 4));
  if (!stamp) {
    return ScanError::kBadChar;
  }
  scan->timestamp_ms = static_cast<uint32_t>(*stamp);
  // Join the data lines (each <= 64 chars + checksum); every line but the last must be full.
  std::string data;
  for (std::size_t i = 1; i < reply.lines.size(); ++i) {
    const std::string& line = reply.lines[i];
    if (line.size() < 2 || line.size() > 65 || (i + 1 < reply.lines.size() && line.size() != 65)) {
      return ScanError::kLength;
    }
    data.append(line, 0, line.size() - 1);
  }
  const std::size_t width = params->intensity ? 6 : 3;
  const std::size_t expected = static_cast<std::size_t>(params->expected_values());
  if (data.size() < expected * width) {
    return ScanError::kTruncated;
  }
  if (data.size() != expected * width) {
    return ScanError::kLength;
  }
  scan->distances.reserve(expected);
  if (params->intensity) {
    scan->intensities.reserve(expected);
  }
  for (std::size_t i = 0; i < expected; ++i) {
    const std::string_view chunk(data.data() + i * width, width);
    const auto distance = scip_decode(chunk.substr(0, 3));
    if (!distance) {
      return ScanError::kBadChar;
    }
    scan->distances.push_back(static_cast<uint32_t>(*distance));
    if (params->intensity) {
      const auto intensity = scip_decode(chunk.substr(3, 3));
      if (!intensity) {
        return ScanError::kBadChar;
      }
      scan->intensities.push_back(static_cast<uint32_t>(*intensity));
    }
  }
  return ScanError::kOk;
}

float range_from_device(uint32_t value, const SensorGeometry& geometry) {
  if (value >= static_cast<uint32_t>(geometry.dmin)) {
    return static_cast<float>(value) / 1000.0f;
  }
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (is_urg04_family(geometry.model)) {
    return value == 0 ? kInf : std::numeric_limits<float>::quiet_NaN();
  }
  if (value == 1) {
    return kInf;
  }
  if (value == 2 || value == 4) {
    return -kInf;
  }
  return std::numeric_limits<float>::quiet_NaN();
}

}  // namespace slamer::urg

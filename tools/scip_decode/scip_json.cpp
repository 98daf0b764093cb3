#include "tools/scip_decode/scip_json.hpp"

#include "common/process/json.hpp"
#include "drivers/urg/scip_scan.hpp"

namespace slamer::urg {

std::string reply_to_json(const Reply& reply) {
  std::string out = "{\"echo\":" + json_quote(reply.echo) + ",\"command\":" + json_quote(reply.command);
  if (!reply.tag.empty()) {
    out += ",\"tag\":" + json_quote(reply.tag);
  }
  out += ",\"status\":" + json_quote(reply.status) + ",\"status_kind\":\"" + status_kind_name(reply.kind()) + "\"";
  out += std::string(",\"checksum_ok\":") + (reply.checksum_ok() ? "true" : "false");
  if (reply.scip1) {
    out += ",\"scip1\":true";
  }
  ScanData scan;
  if (parse_scan_echo(reply.echo)) {
    const ScanError error = decode_scan(reply, &scan);
    if (error == ScanError::kOk) {
      out += ",\"timestamp\":" + std::to_string(scan.timestamp_ms) + ",\"ranges\":[";
      for (std::size_t i = 0; i < scan.distances.size(); ++i) {
        out += (i ? "," : "") + std::to_string(scan.distances[i]);
      }
      out += "]";
      if (!scan.intensities.empty()) {
        out += ",\"intensities\":[";
        for (std::size_t i = 0; i < scan.intensities.size(); ++i) {
          out += (i ? "," : "") + std::to_string(scan.intensities[i]);
        }
        out += "]";
      }
    } else if (reply.kind() == StatusKind::kScanData) {
      out += std::string(",\"scan_error\":\"") + scan_error_name(error) + "\"";
    }
  } else if (!reply.lines.empty()) {
    const KeyValues kv = parse_key_values(reply);
    out += ",\"values\":{";
    for (std::size_t i = 0; i < kv.items.size(); ++i) {
      out += (i ? "," : "") + json_quote(kv.items[i].first) + ":" + json_quote(kv.items[i].second);
    }
    out += "}";
    if (kv.bad_lines > 0) {
      out += ",\"bad_lines\":" + std::to_string(kv.bad_lines);
    }
  }
  return out + "}";
}

}  // namespace slamer::urg

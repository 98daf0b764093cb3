#include "tools/scip_decode/scip_json.hpp"

#include <nlohmann/json.hpp>

#include "drivers/urg/scip_scan.hpp"

namespace slamer::urg {

std::string reply_to_json(const Reply& reply) {
  nlohmann::ordered_json out;
  out["echo"] = reply.echo;
  out["command"] = reply.command;
  if (!reply.tag.empty()) {
    out["tag"] = reply.tag;
  }
  out["status"] = reply.status;
  out["status_kind"] = status_kind_name(reply.kind());
  out["checksum_ok"] = reply.checksum_ok();
  if (reply.scip1) {
    out["scip1"] = true;
  }
  ScanData scan;
  if (parse_scan_echo(reply.echo)) {
    const ScanError error = decode_scan(reply, &scan);
    if (error == ScanError::kOk) {
      out["timestamp"] = scan.timestamp_ms;
      out["ranges"] = scan.distances;
      if (!scan.intensities.empty()) {
        out["intensities"] = scan.intensities;
      }
    } else if (reply.kind() == StatusKind::kScanData) {
      out["scan_error"] = scan_error_name(error);
    }
  } else if (!reply.lines.empty()) {
    const KeyValues kv = parse_key_values(reply);
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const auto& [key, value] : kv.items) {
      values[key] = value;
    }
    out["values"] = values;
    if (kv.bad_lines > 0) {
      out["bad_lines"] = kv.bad_lines;
    }
  }
  // Sensor bytes need not be UTF-8: invalid sequences become U+FFFD instead of an exception.
  return out.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace slamer::urg

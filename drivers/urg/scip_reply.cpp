#include "drivers/urg/scip_reply.hpp"

#include <cctype>

#include "drivers/urg/scip_codec.hpp"

namespace slamer::urg {

void ReplyFramer::feed(std::string_view bytes) {
  if (start_ > 0 && start_ >= buffer_.size() / 2) {
    buffer_.erase(0, start_);
    start_ = 0;
  }
  buffer_.append(bytes);
}

void ReplyFramer::clear() {
  buffer_.clear();
  start_ = 0;
  skipping_ = false;
}

bool ReplyFramer::next(std::vector<std::string>* lines) {
  for (;;) {
    // Find LF LF (CRs in between are tolerated: LF CR LF, CR LF CR LF).
    std::size_t end = std::string::npos;
    std::size_t pos = start_;
    while ((pos = buffer_.find('\n', pos)) != std::string::npos) {
      std::size_t after = pos + 1;
      if (after < buffer_.size() && buffer_[after] == '\r') {
        ++after;
      }
      if (after < buffer_.size() && buffer_[after] == '\n') {
        end = after + 1;
        break;
      }
      if (after >= buffer_.size()) {
        break;
      }
      pos = pos + 1;
    }
    if (end == std::string::npos) {
      if (buffer_.size() - start_ > max_bytes_) {
        if (!skipping_) {
          ++overflows_;
        }
        skipping_ = true;
        // Keep the last byte: it may be the first LF of the blank line.
        start_ = buffer_.size() - 1;
      }
      return false;
    }
    const std::string_view reply(buffer_.data() + start_, end - start_);
    start_ = end;
    if (skipping_) {
      skipping_ = false;
      continue;
    }
    lines->clear();
    std::size_t line_start = 0;
    while (line_start < reply.size()) {
      std::size_t lf = reply.find('\n', line_start);
      std::string_view line = reply.substr(line_start, lf - line_start);
      line_start = lf + 1;
      while (!line.empty() && line.back() == '\r') {
        line.remove_suffix(1);
      }
      while (!line.empty() && line.front() == '\r') {
        line.remove_prefix(1);
      }
      lines->emplace_back(line);
    }
    while (!lines->empty() && lines->back().empty()) {
      lines->pop_back();
    }
    return true;
  }
}

const char* status_kind_name(StatusKind kind) {
  switch (kind) {
    case StatusKind::kOk:
      return "ok";
    case StatusKind::kScanData:
      return "scan_data";
    case StatusKind::kBenign:
      return "benign";
    case StatusKind::kTimeAdjust:
      return "time_adjust";
    case StatusKind::kMalfunction:
      return "malfunction";
    case StatusKind::kCommandError:
      return "command_error";
  }
  return "?";
}

namespace {

bool is_scan_command(std::string_view command) {
  return command == "MD" || command == "ME" || command == "MS" || command == "GD" || command == "GE" ||
         command == "GS" || command == "HD" || command == "HE" || command == "ND" || command == "NE";
}

int two_digit(std::string_view status) {
  if (status.size() != 2 || !std::isdigit(static_cast<unsigned char>(status[0])) ||
      !std::isdigit(static_cast<unsigned char>(status[1]))) {
    return -1;
  }
  return (status[0] - '0') * 10 + (status[1] - '0');
}

}  // namespace

StatusKind classify_status(std::string_view command, std::string_view status) {
  if (status == "00") {
    return StatusKind::kOk;
  }
  if (status == "99" && is_scan_command(command)) {
    return StatusKind::kScanData;
  }
  if (status == "0L") {
    return StatusKind::kMalfunction;
  }
  if (status == "0E" && command != "TM") {
    return StatusKind::kTimeAdjust;
  }
  const int code = two_digit(status);
  if (command == "BM") {
    return code == 2 ? StatusKind::kBenign : code == 1 ? StatusKind::kMalfunction : StatusKind::kCommandError;
  }
  if (command == "TM") {
    return code == 2 || code == 3 ? StatusKind::kBenign : StatusKind::kCommandError;
  }
  if (command == "RB") {
    return code == 1 ? StatusKind::kBenign : StatusKind::kCommandError;
  }
  if (command == "SS") {
    return code == 3 || code == 4 || status == "0F" ? StatusKind::kBenign : StatusKind::kCommandError;
  }
  if (is_scan_command(command)) {
    if (code == 98) {
      return StatusKind::kBenign;
    }
    if (code >= 21 && code <= 97) {
      return StatusKind::kMalfunction;
    }
  }
  return StatusKind::kCommandError;
}

Reply parse_reply(const std::vector<std::string>& lines) {
  Reply reply;
  if (lines.empty()) {
    reply.empty = true;
    return reply;
  }
  reply.echo = lines[0];
  const std::size_t semicolon = reply.echo.find(';');
  const std::string_view head = std::string_view(reply.echo).substr(0, semicolon);
  if (semicolon != std::string::npos) {
    reply.tag = reply.echo.substr(semicolon + 1);
  }
  if (head.rfind("SCIP", 0) == 0) {
    reply.command = std::string(head);
  } else if (!head.empty() && head[0] == '%') {
    reply.command = std::string(head.substr(0, 3));
  } else {
    reply.command = std::string(head.substr(0, 2));
  }
  if (lines.size() < 2) {
    return reply;  // echo only: no status (truncated)
  }
  const std::string& status_line = lines[1];
  if (status_line.size() == 1) {
    reply.scip1 = true;
    reply.status = status_line;
    // SCIP 1.1 commands are one letter ("V", "G00076801").
    if (head.rfind("SCIP", 0) != 0 && (head.size() == 1 || std::isdigit(static_cast<unsigned char>(head[1])))) {
      reply.command = std::string(head.substr(0, 1));
    }
  } else if (status_line.size() == 3) {
    reply.status = status_line.substr(0, 2);
    reply.status_checksum_ok = line_checksum_ok(status_line);
  } else {
    reply.status = status_line;  // malformed status line: checksum cannot be right
  }
  for (std::size_t i = 2; i < lines.size(); ++i) {
    reply.lines.push_back(lines[i]);
    if (!reply.scip1 && !line_checksum_ok(lines[i])) {
      ++reply.bad_checksum_lines;
    }
  }
  return reply;
}

const std::string* KeyValues::find(std::string_view key) const {
  for (const auto& [k, v] : items) {
    if (k == key) {
      return &v;
    }
  }
  return nullptr;
}

namespace {
std::string trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
    text.remove_prefix(1);
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
    text.remove_suffix(1);
  }
  return std::string(text);
}
}  // namespace

KeyValues parse_key_values(const Reply& reply) {
  KeyValues out;
  for (const std::string& line : reply.lines) {
    std::string_view body = line;
    if (!reply.scip1) {
      if (!line_checksum_ok(line)) {
        ++out.bad_lines;
        continue;
      }
      body.remove_suffix(1);
    }
    if (!body.empty() && body.back() == ';') {
      body.remove_suffix(1);
    }
    const std::size_t colon = body.find(':');
    if (colon == std::string_view::npos || colon == 0) {
      ++out.bad_lines;
      continue;
    }
    std::string_view value = body.substr(colon + 1);
    const std::size_t arrow = value.find("<-");
    if (arrow != std::string_view::npos) {
      value = value.substr(0, arrow);
    }
    out.items.emplace_back(std::string(body.substr(0, colon)), trim(value));
  }
  return out;
}

}  // namespace slamer::urg

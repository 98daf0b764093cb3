// SCIP reply framing and parsing (SCIP 2.0 spec p9, p11, p23; scip.md
// "Framing and checksum", "Status codes"): bytes from the sensor are cut into
// replies at the blank line; a reply is echo, status (+ checksum), data lines
// (+ checksum). SCIP 1.1 replies (1-char status, no checksums) are recognised.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace slamer::urg {

// Cuts a byte stream into replies (lists of lines, CR stripped) at LF LF.
// A reply that grows past max_bytes without its blank line is dropped and
// counted; framing resumes at the next blank line.
class ReplyFramer {
 public:
  explicit ReplyFramer(std::size_t max_bytes = 1 << 16) : max_bytes_(max_bytes) {}
  void feed(std::string_view bytes);
  // The next complete reply, or false when none is complete yet.
  bool next(std::vector<std::string>* lines);
  void clear();
  int64_t overflows() const { return overflows_; }
  std::size_t buffered() const { return buffer_.size() - start_; }

 private:
  std::size_t max_bytes_;
  std::string buffer_;
  std::size_t start_ = 0;
  bool skipping_ = false;  // dropping an over-long reply until its blank line
  int64_t overflows_ = 0;
};

enum class StatusKind {
  kOk,            // 00
  kScanData,      // 99 (a scan of a running MD/ME/GD)
  kBenign,        // a per-command code that is not a failure (BM 02, TM 02/03, RB 01, SS 03/04/0F, MD 98)
  kTimeAdjust,    // 0E on QT/BM/MD...: the sensor is stuck in time-adjust mode
  kMalfunction,   // laser/hardware trouble: MD 21-97, BM 01, 0L
  kCommandError,  // anything else: bad parameters, unknown command, denied
};
const char* status_kind_name(StatusKind kind);
// `command` is the 2-char command of the echo ("MD", "QT", ...).
StatusKind classify_status(std::string_view command, std::string_view status);

struct Reply {
  std::string echo;     // first line as received (command + params + ";tag")
  std::string command;  // the command letters: 2 chars ("MD"), or 1 for SCIP 1.1, "SCIP2.0", "%MD"
  std::string tag;      // after ';' in the echo, "" if none
  std::string status;   // "00", "99", ... ("0" / "E" for SCIP 1.1)
  bool scip1 = false;   // 1-char status without checksum: a SCIP 1.1 sensor
  bool status_checksum_ok = false;
  std::vector<std::string> lines;  // data lines with their checksum char
  int bad_checksum_lines = 0;      // data lines whose checksum failed
  bool empty = false;              // no echo at all (stray blank line)

  StatusKind kind() const { return classify_status(command, status); }
  bool checksum_ok() const { return scip1 || (status_checksum_ok && bad_checksum_lines == 0); }
};
// Parses the lines of one framed reply. Never throws.
Reply parse_reply(const std::vector<std::string>& lines);

// VV/PP/II "KEY:value;C" lines: key/value pairs in order; a value with the
// UTM-30LX "<-" comment keeps the text before it (trimmed). Lines that do not
// parse or fail their checksum are skipped and counted.
struct KeyValues {
  std::vector<std::pair<std::string, std::string>> items;
  int bad_lines = 0;
  const std::string* find(std::string_view key) const;
};
KeyValues parse_key_values(const Reply& reply);

}  // namespace slamer::urg

// T-frog text (line mode) protocol pieces (tfrog.md section 5): a command's
// reply (echo, SCIP-style status, body, blank line), VV board identity with the
// YPP:<current>:<age> compatibility rule YP-Spur applies, PP board parameters
// and GETEMBEDDEDPARAM text. Pure: no I/O.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace slamer::tfrog {

// The host protocol YP-Spur speaks: YPP:11:05.
inline constexpr int kHostProtocolCurrent = 11;
inline constexpr int kHostProtocolAge = 5;

struct TextReply {
  std::string echo;
  std::string status;  // e.g. "00P"
  std::vector<std::string> body;
  bool ok() const { return status.size() >= 2 && status.compare(0, 2, "00") == 0; }
};

// Collects the lines of one reply to `command`: lines before the echo are
// skipped; the reply ends at the first empty line after the status.
class ReplyCollector {
 public:
  explicit ReplyCollector(std::string command) : command_(std::move(command)) {}
  // Returns true once the reply is complete (then reply() is valid).
  bool add_line(const std::string& line);
  bool complete() const { return stage_ == Stage::kDone; }
  const TextReply& reply() const { return reply_; }

 private:
  enum class Stage { kEcho, kStatus, kBody, kDone };
  std::string command_;
  Stage stage_ = Stage::kEcho;
  TextReply reply_;
};

struct BoardIdentity {
  std::string vendor;
  std::string product;
  std::string firmware;
  std::string protocol;  // "YPP:11:02"
  std::string serial;
  std::string id;
  int protocol_current = -1;
  int protocol_age = -1;
};
// Parses VV body lines "KEY:value; ". nullopt with *error set when PROT is missing or malformed.
std::optional<BoardIdentity> parse_vv(const std::vector<std::string>& body, std::string* error);
// YP-Spur's rule: device_current >= host_current - host_age and device_current - device_age <= host_current.
bool protocol_compatible(int device_current, int device_age, int host_current = kHostProtocolCurrent,
                         int host_age = kHostProtocolAge);

struct BoardParameters {
  std::string name;  // robot parameter name; "embedded" -> GETEMBEDDEDPARAM
  int pwm_resolution = 0;
  int motor_num = 0;
  std::string param_mode;
};
// Parses PP body lines; nullopt with *error when PWMRES or MOTORNUM is missing or bad.
std::optional<BoardParameters> parse_pp(const std::vector<std::string>& body, std::string* error);

// The body of a GETEMBEDDEDPARAM reply joined back into parameter-file text.
std::string embedded_param_text(const std::vector<std::string>& body);

}  // namespace slamer::tfrog

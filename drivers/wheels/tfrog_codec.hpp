// T-frog TF-2MD3 binary frames (tfrog.md sections 2-4): the 6-bit + 0x40
// payload encoding, host->board command records, the board's odometry and
// interrupt frames, and a splitter that cuts the byte stream into binary
// frames and text lines. Pure: no I/O.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace slamer::tfrog {

inline constexpr uint8_t kStartIsochronous = 0x09;  // commands and odometry
inline constexpr uint8_t kStartInterrupt = 0x07;    // board events
inline constexpr uint8_t kLineFeed = 0x0A;
inline constexpr uint8_t kBroadcastMotor = 0x7E;

// Parameter ids of a command record (tfrog.md section 3).
enum class Param : uint8_t {
  kWRef = 0,
  kWRefHighPrec = 1,
  kPKi = 2,
  kPKv = 3,
  kFrPlus = 4,
  kFrWPlus = 5,
  kFrMinus = 6,
  kFrWMinus = 7,
  kPiKp = 14,
  kPiKi = 15,
  kPwmMax = 16,
  kPwmMin = 17,
  kToqMax = 18,
  kToqMin = 19,
  kIntMax = 20,
  kIntMin = 21,
  kToqOffset = 22,
  kToqLimit = 23,
  kEncRev = 24,
  kMotorPhase = 25,
  kVsrc = 26,
  kInertiaSelf = 27,
  kInertiaCross = 28,
  kEncType = 29,
  kControlCycle = 30,
  kEncDiv = 31,
  kEncDenominator = 32,
  kHallDelayFactor = 33,
  kLrCutoffVel = 34,
  kVmin = 35,
  kServo = 64,
  kWatchDogLimit = 65,
  kPhaseOffset = 99,
  kProtocolVersion = 100,
  kPing = 101,
};

enum class ServoLevel : int32_t { kStop = 0, kCounter = 1, kTorque = 2, kVelocity = 3, kPosition = 4, kOpenFree = 5 };

// Interrupt events (board -> host) and error_state bits.
enum class Event : uint8_t { kIndexRise = 0, kIndexFall = 1, kErrorState = 2, kPingResponse = 3, kDebugDump = 4 };
inline constexpr int32_t kErrorLowVoltage = 0x01;
inline constexpr int32_t kErrorHallSeq = 0x02;
inline constexpr int32_t kErrorHallEnc = 0x04;
inline constexpr int32_t kErrorWatchdog = 0x08;
inline constexpr int32_t kErrorEeprom = 0x10;
inline constexpr int32_t kErrorInternal = 0x20;
// "LOW_VOLTAGE|WATCHDOG" style names of the set bits; "" for 0.
std::string error_bits_text(int32_t bits);

// Raw bytes -> printable chars 0x40..0x7F, MSB first in 6-bit groups.
std::string encode_payload(std::span<const uint8_t> raw);
// Chars -> raw bytes; nullopt if any char is outside 0x40..0x7F.
std::optional<std::vector<uint8_t>> decode_payload(std::string_view chars);
// start byte + encoded payload + LF.
std::vector<uint8_t> encode_frame(uint8_t start, std::span<const uint8_t> raw);

struct Command {
  uint8_t param = 0;
  uint8_t motor = 0;
  int32_t value = 0;
  bool operator==(const Command&) const = default;
};
std::array<uint8_t, 6> command_record(const Command& command);
std::optional<Command> parse_command_record(std::span<const uint8_t> raw);  // exactly 6 bytes
// A command as a 0x09 frame (10 bytes on the wire).
std::vector<uint8_t> encode_command(const Command& command);
std::vector<uint8_t> encode_command(Param param, uint8_t motor, int32_t value);

// Board -> host odometry frame: int16 BE cnt[motors], pwm[motors], then `words` AD/IO words.
struct OdometryFrame {
  std::vector<int16_t> count;
  std::vector<int16_t> pwm;
  std::vector<uint16_t> words;  // top 4 bits channel, low 12 bits value
};
// nullopt unless raw.size() == 2 * (2 * motors + words).
std::optional<OdometryFrame> decode_odometry(std::span<const uint8_t> raw, int motors, int words);
std::vector<uint8_t> encode_odometry(const OdometryFrame& frame);  // raw bytes (for the emulator)

struct InterruptEvent {
  uint8_t event = 0;
  uint8_t motor = 0;
  int32_t value = 0;
};
// 6 decoded bytes; nullopt for any other length (debug dumps are variable and skipped).
std::optional<InterruptEvent> decode_interrupt(std::span<const uint8_t> raw);

// One unit of the board's byte stream.
struct StreamItem {
  enum class Kind { kIsochronous, kInterrupt, kText, kBadFrame };
  Kind kind = Kind::kText;
  std::vector<uint8_t> raw;  // decoded payload of a binary frame
  std::string text;          // a text line without its LF
};

// Cuts bytes into binary frames (start byte .. LF) and text lines. A frame
// with a char below 0x40, interrupted by another start byte, or longer than
// max_chars is reported as kBadFrame; text lines longer than max_chars are cut.
class StreamSplitter {
 public:
  explicit StreamSplitter(std::size_t max_chars = 2048) : max_chars_(max_chars) {}
  void feed(std::span<const uint8_t> bytes, std::vector<StreamItem>* out);
  void reset();
  // Bytes of an incomplete item held since the last feed.
  std::size_t pending() const { return buffer_.size(); }

 private:
  void finish(std::vector<StreamItem>* out);
  std::size_t max_chars_;
  uint8_t start_ = 0;  // 0: text
  bool bad_ = false;
  std::string buffer_;
};

}  // namespace slamer::tfrog

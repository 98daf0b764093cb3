// Wheel encoders over CAN: frame layout per wheel from YAML (id standard or
// extended, byte offset, width, endianness, signedness, counts or velocity),
// a CANopen preset (TPDO carrying position actual value 0x6064, int32 LE),
// error frames (bus-off, error-passive, lost arbitration) and candump -l log
// lines. Wheel 0 is motor 0 (right), wheel 1 motor 1 (left), raw counts in the
// same sign convention as the T-frog motors so the robot's signed radii apply.
// Pure: frames in (with their receive time), tick samples out.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "drivers/wheels/wheel_odometry.hpp"

namespace slamer::can {

struct CanFrame {
  uint32_t id = 0;  // without flags
  bool extended = false;
  bool rtr = false;
  bool error = false;  // an error frame: id holds the CAN_ERR_* class bits
  uint8_t len = 0;
  std::array<uint8_t, 8> data{};
  int64_t utime = 0;
};
// The 16 bytes of a Linux struct can_frame; nullopt for another size or len > 8.
std::optional<CanFrame> parse_can_frame(std::span<const uint8_t> bytes);
std::array<uint8_t, 16> to_can_frame_bytes(const CanFrame& frame);
// "(1436509052.249713) can0 123#11223344" -> frame; nullopt with *error for anything else.
std::optional<CanFrame> parse_candump_line(const std::string& line, std::string* error);

struct WheelField {
  int64_t id = 0;
  bool extended = false;
  int offset = 0;
  int width = 4;  // bytes: 1, 2, 4 or 8
  bool big_endian = false;
  bool is_signed = true;
  bool velocity = false;  // counts per second instead of a position
  double scale = 1.0;     // raw value * scale = motor counts (or counts/s)
};

struct CanLayout {
  std::string preset = "none";        // "canopen": TPDO position actual value 0x6064
  int tpdo = 1;                       // 1..4 -> COB-ID 0x180/0x280/0x380/0x480 + node
  std::array<int, 2> nodes = {1, 2};  // CANopen node ids of motor 0 (right) and motor 1 (left)
  std::array<WheelField, 2> wheels;   // used when preset is "none"
  double silence_timeout = 0.3;       // [s] without frames: degraded
};
void read_options(const ConfigReader& reader, CanLayout* layout);
// The effective fields (the preset expanded).
std::array<WheelField, 2> wheel_fields(const CanLayout& layout);
// Reads the field from a frame's data; nullopt when the frame is too short.
std::optional<int64_t> extract(const WheelField& field, const CanFrame& frame);

struct BusStatus {
  bool bus_off = false;
  bool error_passive = false;
  int64_t error_frames = 0;
  int64_t lost_arbitration = 0;
  int64_t restarts = 0;
  int64_t short_frames = 0;  // a configured id with too few bytes
  int64_t frames = 0;
  std::string last_problem;
};

struct TickSample {
  int64_t utime = 0;
  std::array<int64_t, 2> ticks{};  // cumulative motor counts
  std::array<int64_t, 2> delta{};
};

class CanDecoder {
 public:
  explicit CanDecoder(const CanLayout& layout) : fields_(wheel_fields(layout)) {}
  // A sample once both wheels have reported since the last one.
  std::optional<TickSample> feed(const CanFrame& frame);
  const BusStatus& status() const { return status_; }
  std::vector<uint32_t> ids() const;

 private:
  void on_error(const CanFrame& frame);
  std::array<WheelField, 2> fields_;
  BusStatus status_;
  std::array<std::optional<int64_t>, 2> previous_;
  std::array<int64_t, 2> previous_utime_{};
  std::array<double, 2> velocity_carry_{};
  std::array<int64_t, 2> cumulative_{};
  std::array<int64_t, 2> pending_{};
  std::array<bool, 2> fresh_{};
};

}  // namespace slamer::can

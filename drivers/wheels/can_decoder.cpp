#include "drivers/wheels/can_decoder.hpp"

#include <linux/can.h>
#include <linux/can/error.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace slamer::can {

std::optional<CanFrame> parse_can_frame(std::span<const uint8_t> bytes) {
  if (bytes.size() != sizeof(can_frame)) {
    return std::nullopt;
  }
  can_frame raw{};
  std::memcpy(&raw, bytes.data(), sizeof(raw));
  if (raw.len > 8) {
    return std::nullopt;
  }
  CanFrame frame;
  frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
  frame.rtr = (raw.can_id & CAN_RTR_FLAG) != 0;
  frame.error = (raw.can_id & CAN_ERR_FLAG) != 0;
  frame.id = frame.error      ? (raw.can_id & CAN_ERR_MASK)
             : frame.extended ? (raw.can_id & CAN_EFF_MASK)
                              : (raw.can_id & CAN_SFF_MASK);
  frame.len = raw.len;
  std::memcpy(frame.data.data(), raw.data, 8);
  return frame;
}

std::array<uint8_t, 16> to_can_frame_bytes(const CanFrame& frame) {
  can_frame raw{};
  raw.can_id = frame.id | (frame.extended ? CAN_EFF_FLAG : 0u) | (frame.rtr ? CAN_RTR_FLAG : 0u) |
               (frame.error ? CAN_ERR_FLAG : 0u);
  raw.len = frame.len;
  std::memcpy(raw.data, frame.data.data(), 8);
  std::array<uint8_t, 16> bytes{};
  std::memcpy(bytes.data(), &raw, sizeof(raw));
  return bytes;
}

namespace {
bool hex_value(std::string_view text, uint64_t* value) {
  if (text.empty() || text.size() > 16) {
    return false;
  }
  uint64_t v = 0;
  for (const char c : text) {
    int d = 0;
    if (c >= '0' && c <= '9') {
      d = c - '0';
    } else if (c >= 'a' && c <= 'f') {
      d = c - 'a' + 10;
    } else if (c >= 'A' && c <= 'F') {
      d = c - 'A' + 10;
    } else {
      return false;
    }
    v = (v << 4) | static_cast<uint64_t>(d);
  }
  *value = v;
  return true;
}
}  // namespace

std::optional<CanFrame> parse_candump_line(const std::string& line, std::string* error) {
  std::istringstream in(line);
  std::string stamp;
  std::string interface;
  std::string body;
  if (!(in >> stamp >> interface >> body) || stamp.size() < 3 || stamp.front() != '(' || stamp.back() != ')') {
    *error = "not a candump -l line";
    return std::nullopt;
  }
  const std::string seconds = stamp.substr(1, stamp.size() - 2);
  const auto dot = seconds.find('.');
  uint64_t sec = 0;
  uint64_t frac = 0;
  // Digits, one dot, 6 fraction digits and at most 12 of seconds (stoull neither throws nor overflows).
  if (dot == std::string::npos || dot == 0 || dot > 12 || seconds.size() - dot - 1 != 6 ||
      seconds.find_first_not_of("0123456789.") != std::string::npos ||
      seconds.find('.', dot + 1) != std::string::npos) {
    *error = "bad timestamp '" + stamp + "'";
    return std::nullopt;
  }
  sec = std::stoull(seconds.substr(0, dot));
  frac = std::stoull(seconds.substr(dot + 1));
  const auto hash = body.find('#');
  if (hash == std::string::npos || (hash != 3 && hash != 8)) {
    *error = "bad frame '" + body + "'";
    return std::nullopt;
  }
  if (body.compare(hash, 2, "##") == 0) {
    *error = "CAN FD frames are not supported";
    return std::nullopt;
  }
  uint64_t id = 0;
  if (!hex_value(std::string_view(body).substr(0, hash), &id)) {
    *error = "bad id in '" + body + "'";
    return std::nullopt;
  }
  CanFrame frame;
  frame.utime = static_cast<int64_t>(sec * 1000000 + frac);
  if (hash == 8) {
    frame.error = (id & CAN_ERR_FLAG) != 0;
    frame.extended = !frame.error;
    frame.id = static_cast<uint32_t>(id & (frame.error ? CAN_ERR_MASK : CAN_EFF_MASK));
  } else {
    frame.id = static_cast<uint32_t>(id);
    if (id > CAN_SFF_MASK) {
      *error = "bad standard id in '" + body + "'";
      return std::nullopt;
    }
  }
  std::string_view data = std::string_view(body).substr(hash + 1);
  if (!data.empty() && (data[0] == 'R' || data[0] == 'r')) {
    frame.rtr = true;
    return frame;
  }
  if (data.size() % 2 != 0 || data.size() > 16) {
    *error = "bad data in '" + body + "'";
    return std::nullopt;
  }
  for (std::size_t i = 0; i < data.size(); i += 2) {
    uint64_t byte = 0;
    if (!hex_value(data.substr(i, 2), &byte)) {
      *error = "bad data in '" + body + "'";
      return std::nullopt;
    }
    frame.data[i / 2] = static_cast<uint8_t>(byte);
  }
  frame.len = static_cast<uint8_t>(data.size() / 2);
  return frame;
}

namespace {
void read_field(const ConfigReader& reader, WheelField* field) {
  reader.read("id", &field->id, in_range(0, 0x1FFFFFFF));
  reader.read("extended", &field->extended);
  reader.read("offset", &field->offset, in_range(0, 7));
  reader.read("width", &field->width, in_range(1, 8));
  if (field->width != 1 && field->width != 2 && field->width != 4 && field->width != 8) {
    reader.fail("width", "must be 1, 2, 4 or 8 bytes");
  }
  if (field->offset + field->width > 8) {
    reader.fail("offset", "offset + width must be <= 8");
  }
  if (!field->extended && field->id > 0x7FF) {
    reader.fail("id", "a standard id must be <= 0x7FF (set extended: true)");
  }
  std::string endian = field->big_endian ? "big" : "little";
  reader.read_choice("endian", &endian, {"big", "little"});
  field->big_endian = endian == "big";
  reader.read("signed", &field->is_signed);
  std::string kind = field->velocity ? "velocity" : "counts";
  reader.read_choice("kind", &kind, {"counts", "velocity"});
  field->velocity = kind == "velocity";
  reader.read("scale", &field->scale);
  if (field->scale == 0.0) {
    reader.fail("scale", "must not be 0");
  }
}
}  // namespace

void read_options(const ConfigReader& reader, CanLayout* layout) {
  reader.read_choice("preset", &layout->preset, {"none", "canopen"});
  reader.read("tpdo", &layout->tpdo, in_range(1, 4));
  std::vector<double> nodes = {static_cast<double>(layout->nodes[0]), static_cast<double>(layout->nodes[1])};
  reader.read("nodes", &nodes, in_range(1, 127), 2);
  layout->nodes = {static_cast<int>(nodes[0]), static_cast<int>(nodes[1])};
  read_field(reader.section("right"), &layout->wheels[0]);
  read_field(reader.section("left"), &layout->wheels[1]);
  reader.read("silence_timeout", &layout->silence_timeout, positive());
}

std::array<WheelField, 2> wheel_fields(const CanLayout& layout) {
  if (layout.preset != "canopen") {
    return layout.wheels;
  }
  std::array<WheelField, 2> fields;
  for (std::size_t i = 0; i < 2; ++i) {
    fields[i].id = 0x80 + 0x100 * layout.tpdo + layout.nodes[i];
    fields[i].extended = false;
    fields[i].offset = 0;
    fields[i].width = 4;
    fields[i].big_endian = false;
    fields[i].is_signed = true;
    fields[i].velocity = false;
    fields[i].scale = layout.wheels[i].scale;
  }
  return fields;
}

std::optional<int64_t> extract(const WheelField& field, const CanFrame& frame) {
  if (frame.rtr || field.offset + field.width > frame.len) {
    return std::nullopt;
  }
  uint64_t value = 0;
  for (int i = 0; i < field.width; ++i) {
    const int at = field.big_endian ? field.offset + i : field.offset + field.width - 1 - i;
    value = (value << 8) | frame.data[static_cast<std::size_t>(at)];
  }
  const int bits = 8 * field.width;
  if (field.is_signed && bits < 64 && (value >> (bits - 1)) != 0) {
    value |= ~uint64_t{0} << bits;
  }
  return static_cast<int64_t>(value);
}

std::vector<uint32_t> CanDecoder::ids() const {
  return {static_cast<uint32_t>(fields_[0].id), static_cast<uint32_t>(fields_[1].id)};
}

void CanDecoder::on_error(const CanFrame& frame) {
  ++status_.error_frames;
  if ((frame.id & CAN_ERR_BUSOFF) != 0) {
    status_.bus_off = true;
    status_.last_problem = "CAN bus-off";
  }
  if ((frame.id & CAN_ERR_LOSTARB) != 0) {
    ++status_.lost_arbitration;
  }
  if ((frame.id & CAN_ERR_CRTL) != 0 && frame.len >= 2) {
    const uint8_t ctrl = frame.data[1];
    if ((ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      status_.error_passive = true;
      status_.last_problem = "CAN controller error-passive";
    }
    if (ctrl == CAN_ERR_CRTL_ACTIVE) {
      status_.error_passive = false;
    }
  }
  if ((frame.id & CAN_ERR_RESTARTED) != 0) {
    ++status_.restarts;
    status_.bus_off = false;
    status_.error_passive = false;
  }
}

std::optional<TickSample> CanDecoder::feed(const CanFrame& frame) {
  if (frame.error) {
    on_error(frame);
    return std::nullopt;
  }
  bool matched = false;
  for (std::size_t i = 0; i < 2; ++i) {
    const WheelField& field = fields_[i];
    if (frame.id != field.id || frame.extended != field.extended) {
      continue;
    }
    matched = true;
    const auto value = extract(field, frame);
    if (!value) {
      ++status_.short_frames;
      status_.last_problem = "CAN id " + std::to_string(frame.id) + ": frame too short";
      continue;
    }
    if (status_.bus_off) {  // frames flow again: the bus recovered
      status_.bus_off = false;
    }
    int64_t delta = 0;
    if (field.velocity) {
      if (previous_[i]) {
        const double dt = static_cast<double>(frame.utime - previous_utime_[i]) * 1e-6;
        const double counts = static_cast<double>(*previous_[i]) * field.scale * std::max(dt, 0.0) + velocity_carry_[i];
        delta = static_cast<int64_t>(std::llround(counts));
        velocity_carry_[i] = counts - static_cast<double>(delta);
      }
    } else if (previous_[i]) {
      const int bits = 8 * field.width;
      uint64_t diff = static_cast<uint64_t>(*value) - static_cast<uint64_t>(*previous_[i]);
      if (bits < 64) {  // wrap at the field's width
        diff &= (uint64_t{1} << bits) - 1;
        if ((diff >> (bits - 1)) != 0) {
          diff |= ~uint64_t{0} << bits;
        }
      }
      delta = static_cast<int64_t>(std::llround(static_cast<double>(static_cast<int64_t>(diff)) * field.scale));
    }
    previous_[i] = value;
    previous_utime_[i] = frame.utime;
    cumulative_[i] += delta;
    pending_[i] += delta;
    fresh_[i] = true;
  }
  if (!matched) {
    return std::nullopt;
  }
  ++status_.frames;
  if (!(fresh_[0] && fresh_[1])) {
    return std::nullopt;
  }
  TickSample sample{frame.utime, cumulative_, pending_};
  pending_ = {0, 0};
  fresh_ = {false, false};
  return sample;
}

}  // namespace slamer::can

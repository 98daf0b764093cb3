#include "drivers/wheels/tfrog_codec.hpp"

namespace slamer::tfrog {

std::string error_bits_text(int32_t bits) {
  static constexpr std::pair<int32_t, const char*> kNames[] = {
      {kErrorLowVoltage, "LOW_VOLTAGE"}, {kErrorHallSeq, "HALL_SEQ"}, {kErrorHallEnc, "HALL_ENC"},
      {kErrorWatchdog, "WATCHDOG"},      {kErrorEeprom, "EEPROM"},    {kErrorInternal, "INTERNAL"}};
  std::string text;
  int32_t rest = bits;
  for (const auto& [bit, name] : kNames) {
    if ((bits & bit) != 0) {
      text += (text.empty() ? "" : "|");
      text += name;
      rest &= ~bit;
    }
  }
  if (rest != 0) {
    text += (text.empty() ? "" : "|") + std::string("0x") + std::to_string(rest);
  }
  return text;
}

std::string encode_payload(std::span<const uint8_t> raw) {
  std::string out;
  out.reserve((raw.size() * 8 + 5) / 6);
  uint32_t bits = 0;
  int nbits = 0;
  for (const uint8_t byte : raw) {
    bits = (bits << 8) | byte;
    nbits += 8;
    while (nbits >= 6) {
      nbits -= 6;
      out.push_back(static_cast<char>(0x40 + ((bits >> nbits) & 0x3F)));
    }
    bits &= (1u << nbits) - 1u;
  }
  if (nbits > 0) {
    out.push_back(static_cast<char>(0x40 + ((bits << (6 - nbits)) & 0x3F)));
  }
  return out;
}

std::optional<std::vector<uint8_t>> decode_payload(std::string_view chars) {
  std::vector<uint8_t> out;
  out.reserve(chars.size() * 6 / 8);
  uint32_t bits = 0;
  int nbits = 0;
  for (const char c : chars) {
    const auto u = static_cast<uint8_t>(c);
    if (u < 0x40 || u > 0x7F) {
      return std::nullopt;
    }
    bits = (bits << 6) | (u - 0x40u);
    nbits += 6;
    if (nbits >= 8) {
      nbits -= 8;
      out.push_back(static_cast<uint8_t>((bits >> nbits) & 0xFF));
      bits &= (1u << nbits) - 1u;
    }
  }
  return out;
}

std::vector<uint8_t> encode_frame(uint8_t start, std::span<const uint8_t> raw) {
  const std::string chars = encode_payload(raw);
  std::vector<uint8_t> out;
  out.reserve(chars.size() + 2);
  out.push_back(start);
  out.insert(out.end(), chars.begin(), chars.end());
  out.push_back(kLineFeed);
  return out;
}

std::array<uint8_t, 6> command_record(const Command& command) {
  const auto value = static_cast<uint32_t>(command.value);
  return {command.param,
          command.motor,
          static_cast<uint8_t>(value >> 24),
          static_cast<uint8_t>(value >> 16),
          static_cast<uint8_t>(value >> 8),
          static_cast<uint8_t>(value)};
}

std::optional<Command> parse_command_record(std::span<const uint8_t> raw) {
  if (raw.size() != 6) {
    return std::nullopt;
  }
  const uint32_t value = (uint32_t{raw[2]} << 24) | (uint32_t{raw[3]} << 16) | (uint32_t{raw[4]} << 8) | raw[5];
  return Command{raw[0], raw[1], static_cast<int32_t>(value)};
}

std::vector<uint8_t> encode_command(const Command& command) {
  const auto record = command_record(command);
  return encode_frame(kStartIsochronous, record);
}

std::vector<uint8_t> encode_command(Param param, uint8_t motor, int32_t value) {
  return encode_command(Command{static_cast<uint8_t>(param), motor, value});
}

namespace {
uint16_t be16(std::span<const uint8_t> raw, std::size_t at) {
  return static_cast<uint16_t>((raw[at] << 8) | raw[at + 1]);
}
void put16(std::vector<uint8_t>* out, uint16_t value) {
  out->push_back(static_cast<uint8_t>(value >> 8));
  out->push_back(static_cast<uint8_t>(value));
}
}  // namespace

std::optional<OdometryFrame> decode_odometry(std::span<const uint8_t> raw, int motors, int words) {
  if (motors < 0 || words < 0 || raw.size() != static_cast<std::size_t>(2 * (2 * motors + words))) {
    return std::nullopt;
  }
  OdometryFrame frame;
  std::size_t at = 0;
  for (int i = 0; i < motors; ++i, at += 2) {
    frame.count.push_back(static_cast<int16_t>(be16(raw, at)));
  }
  for (int i = 0; i < motors; ++i, at += 2) {
    frame.pwm.push_back(static_cast<int16_t>(be16(raw, at)));
  }
  for (int i = 0; i < words; ++i, at += 2) {
    frame.words.push_back(be16(raw, at));
  }
  return frame;
}

std::vector<uint8_t> encode_odometry(const OdometryFrame& frame) {
  std::vector<uint8_t> raw;
  for (const int16_t c : frame.count) {
    put16(&raw, static_cast<uint16_t>(c));
  }
  for (const int16_t p : frame.pwm) {
    put16(&raw, static_cast<uint16_t>(p));
  }
  for (const uint16_t w : frame.words) {
    put16(&raw, w);
  }
  return raw;
}

std::optional<InterruptEvent> decode_interrupt(std::span<const uint8_t> raw) {
  const auto record = parse_command_record(raw);
  if (!record) {
    return std::nullopt;
  }
  return InterruptEvent{record->param, record->motor, record->value};
}

void StreamSplitter::reset() {
  start_ = 0;
  bad_ = false;
  buffer_.clear();
}

void StreamSplitter::finish(std::vector<StreamItem>* out) {
  StreamItem item;
  if (start_ == 0) {
    item.kind = StreamItem::Kind::kText;
    item.text = buffer_;
    if (!item.text.empty() && item.text.back() == '\r') {
      item.text.pop_back();
    }
  } else {
    auto raw = bad_ ? std::nullopt : decode_payload(buffer_);
    if (raw) {
      item.kind = start_ == kStartIsochronous ? StreamItem::Kind::kIsochronous : StreamItem::Kind::kInterrupt;
      item.raw = std::move(*raw);
    } else {
      item.kind = StreamItem::Kind::kBadFrame;
    }
  }
  out->push_back(std::move(item));
  reset();
}

void StreamSplitter::feed(std::span<const uint8_t> bytes, std::vector<StreamItem>* out) {
  for (const uint8_t byte : bytes) {
    if (byte == kLineFeed) {
      finish(out);
      continue;
    }
    if (byte == kStartIsochronous || byte == kStartInterrupt) {
      if (start_ != 0) {  // a frame cut short by the next one
        bad_ = true;
        finish(out);
      } else if (!buffer_.empty()) {  // text without its LF: drop it
        buffer_.clear();
      }
      start_ = byte;
      continue;
    }
    if (buffer_.size() >= max_chars_) {
      if (start_ != 0) {
        bad_ = true;
      }
      continue;
    }
    if (start_ != 0 && byte < 0x40) {
      bad_ = true;
    }
    buffer_.push_back(static_cast<char>(byte));
  }
}

}  // namespace slamer::tfrog

#include "common/process/event_log.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace slamer {
namespace {

constexpr uint32_t kSyncWord = 0xEDA1DA01;
constexpr std::size_t kReadChunk = 64 << 10;

uint64_t big_endian(const uint8_t* p, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value = (value << 8) | p[i];
  }
  return value;
}

}  // namespace

EventParse parse_log_event(std::span<const uint8_t> bytes, LogEvent* event, std::size_t* used) {
  // Check what is there before waiting for more: a bad sync word or length is damage now.
  if (bytes.size() >= 4 && big_endian(bytes.data(), 4) != kSyncWord) {
    return EventParse::kDamaged;
  }
  if (bytes.size() < kLogEventHeaderBytes) {
    return EventParse::kIncomplete;
  }
  const uint64_t channel_length = big_endian(bytes.data() + 20, 4);
  const uint64_t data_length = big_endian(bytes.data() + 24, 4);
  if (channel_length == 0 || channel_length > kMaxLogChannelLength || data_length > kMaxLogEventBytes) {
    return EventParse::kDamaged;
  }
  const std::size_t channel_end = kLogEventHeaderBytes + channel_length;
  const std::size_t checked = std::min(bytes.size(), channel_end);
  for (std::size_t i = kLogEventHeaderBytes; i < checked; ++i) {
    if (bytes[i] < 0x20 || bytes[i] > 0x7e) {
      return EventParse::kDamaged;  // channel names are printable ASCII
    }
  }
  const std::size_t total = channel_end + data_length;
  if (bytes.size() < total) {
    return EventParse::kIncomplete;
  }
  event->event_number = static_cast<int64_t>(big_endian(bytes.data() + 4, 8));
  event->timestamp = static_cast<int64_t>(big_endian(bytes.data() + 12, 8));
  event->channel.assign(reinterpret_cast<const char*>(bytes.data() + kLogEventHeaderBytes), channel_length);
  event->data.assign(bytes.begin() + static_cast<std::ptrdiff_t>(channel_end),
                     bytes.begin() + static_cast<std::ptrdiff_t>(total));
  *used = total;
  return EventParse::kEvent;
}

EventLogReader::EventLogReader(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "rb")) {
  if (file_ == nullptr) {
    throw std::runtime_error("cannot read log " + path + ": " + std::strerror(errno));
  }
  std::error_code error;
  size_ = std::max(1.0, static_cast<double>(std::filesystem::file_size(path, error)));
}

EventLogReader::EventLogReader(std::FILE* file, std::string name) : path_(std::move(name)), file_(file) {
  if (file_ == nullptr) {
    throw std::runtime_error("cannot read log " + path_);
  }
}

EventLogReader::~EventLogReader() {
  std::fclose(file_);
}

bool EventLogReader::fill(std::size_t wanted) {
  if (start_ > 0 && start_ >= buffer_.size() / 2) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  while (buffer_.size() - start_ < wanted) {
    const std::size_t old = buffer_.size();
    const std::size_t chunk = std::max(kReadChunk, wanted - (old - start_));
    buffer_.resize(old + chunk);
    const std::size_t got = std::fread(buffer_.data() + old, 1, chunk, file_);
    buffer_.resize(old + got);
    if (got == 0) {
      return false;
    }
  }
  return true;
}

std::optional<LogEvent> EventLogReader::next() {
  LogEvent event;
  std::size_t wanted = kLogEventHeaderBytes;
  for (;;) {
    const bool more = fill(wanted);
    const std::span<const uint8_t> bytes(buffer_.data() + start_, buffer_.size() - start_);
    if (bytes.empty()) {
      return std::nullopt;
    }
    std::size_t used = 0;
    const EventParse parse = parse_log_event(bytes, &event, &used);
    if (parse == EventParse::kEvent) {
      start_ += used;
      consumed_ += static_cast<int64_t>(used);
      in_damage_ = false;
      return event;
    }
    if (parse == EventParse::kIncomplete && more) {
      // The header is sound: read the rest of the event.
      wanted = bytes.size() < kLogEventHeaderBytes
                   ? kLogEventHeaderBytes
                   : kLogEventHeaderBytes + big_endian(bytes.data() + 20, 4) + big_endian(bytes.data() + 24, 4);
      continue;
    }
    if (parse == EventParse::kIncomplete) {
      // The file ends: inside an event if what is left starts like one.
      const uint8_t sync[4] = {0xED, 0xA1, 0xDA, 0x01};
      if (bytes.size() >= 4 || std::equal(bytes.begin(), bytes.end(), sync)) {
        truncated_ = true;
      } else if (!in_damage_) {
        ++damaged_stretches_;
      }
      damaged_bytes_ += static_cast<int64_t>(bytes.size());
      consumed_ += static_cast<int64_t>(bytes.size());
      start_ = buffer_.size();
      return std::nullopt;
    }
    // Damaged: skip to the next sync word and try there.
    if (!in_damage_) {
      ++damaged_stretches_;
      in_damage_ = true;
    }
    std::size_t skip = 1;
    while (skip + 4 <= bytes.size() && big_endian(bytes.data() + skip, 4) != kSyncWord) {
      ++skip;
    }
    if (skip + 4 > bytes.size()) {
      skip = bytes.size() > 3 ? bytes.size() - 3 : bytes.size();  // a sync word may straddle the next read
      if (!more) {
        skip = bytes.size();
      }
    }
    start_ += skip;
    consumed_ += static_cast<int64_t>(skip);
    damaged_bytes_ += static_cast<int64_t>(skip);
    wanted = kLogEventHeaderBytes;
  }
}

double EventLogReader::fraction_read() const {
  return std::min(1.0, static_cast<double>(consumed_) / size_);
}

std::string EventLogReader::problems() const {
  if (damaged_bytes_ == 0) {
    return "";
  }
  std::string text = path_ + ": skipped " + std::to_string(damaged_bytes_) + " damaged bytes";
  if (damaged_stretches_ > 0) {
    text += " in " + std::to_string(damaged_stretches_) + " place(s)";
  }
  if (truncated_) {
    text += damaged_stretches_ > 0 ? "; it ends inside an event (cut off while written?)"
                                   : " at its end: it ends inside an event (cut off while written?)";
  }
  return text;
}

}  // namespace slamer

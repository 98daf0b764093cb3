// The thin I/O under the wheel driver: the T-frog's USB serial port (raw 8N1,
// non-blocking) and CAN_RAW sockets (filters for the configured ids, error
// frames on, SO_TIMESTAMP), plus reading one can_frame from any datagram fd
// with recvmsg, so tests feed real 16-byte frames over a socketpair. Every
// function throws std::runtime_error with a one-line reason or returns a status.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "drivers/wheels/can_decoder.hpp"

namespace slamer {

// Opens `path` (following symlinks at each call) raw, non-blocking; -1 with *error on failure.
int open_serial(const std::string& path, std::string* error);

// A CAN_RAW socket bound to `interface` receiving `ids` and error frames.
int open_can_socket(const std::string& interface, const std::vector<uint32_t>& ids, bool extended, std::string* error);

enum class ReadResult { kFrame, kWouldBlock, kClosed, kError, kBadSize };
// Reads one datagram; the receive time from SO_TIMESTAMP when present, else `fallback_utime`.
ReadResult read_can_frame(int fd, int64_t fallback_utime, can::CanFrame* frame, std::string* error);
// Asks the kernel for SO_TIMESTAMP on `fd` (works for CAN and AF_UNIX sockets).
bool enable_timestamps(int fd);

}  // namespace slamer

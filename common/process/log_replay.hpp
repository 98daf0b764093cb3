// Offline mode of an algorithm process: reads an LCM log, hands the events of
// the channels it handles to a callback, copies every other event to the
// output log unchanged (except `replaced` channels: the process's own
// outputs, which an earlier run may have left in the log), and writes what
// the callback produces right after the event that caused it, with that
// event's timestamp. No clock and no
// network: the output depends only on the input (and the process's seed).
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "common/process/decode.hpp"

namespace slamer {

struct OutputEvent {
  std::string channel;
  std::vector<uint8_t> bytes;
};

struct ReplayStats {
  int64_t events_in = 0;
  int64_t events_replaced = 0;  // earlier outputs left out
  int64_t events_handled = 0;
  int64_t events_out = 0;
  int64_t handler_errors = 0;
};

// `handle` gets (channel, bytes, timestamp) of each event on `channels` and
// appends its outputs. `finish` (may be empty) appends what is still pending
// at the end of the log; it is written with the last event's timestamp.
// On a terminal, the percentage read goes to stderr as "PROGRAM: NN%";
// damaged stretches of the input log are skipped (event_log.hpp) and logged
// as one warning of `program`. Throws std::runtime_error if a log cannot be
// opened or written.
ReplayStats replay_log(const std::string& program, const std::string& in_path, const std::string& out_path,
                       const std::set<std::string>& channels, const std::set<std::string>& replaced,
                       const std::function<void(const std::string&, const std::vector<uint8_t>&, int64_t,
                                                std::vector<OutputEvent>*)>& handle,
                       const std::function<void(std::vector<OutputEvent>*)>& finish = {});

template <class Msg>
OutputEvent encode_event(const std::string& channel, const Msg& msg) {
  OutputEvent event{channel, std::vector<uint8_t>(static_cast<std::size_t>(msg.getEncodedSize()))};
  msg.encode(event.bytes.data(), 0, static_cast<int>(event.bytes.size()));
  return event;
}

}  // namespace slamer

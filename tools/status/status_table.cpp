#include "tools/status/status_table.hpp"

#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>
#include "slamer/channel_stats_t.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, StatusMonitorOptions* options) {
  reader.read("channel", &options->channel);
  reader.read("stale_after", &options->stale_after, positive());
  if (options->channel.empty()) {
    reader.fail("channel", "must not be empty");
  }
}

void read_options(const ConfigReader& reader, StatusProcessConfig* config) {
  read_options(reader.section("process"), &config->process);
  read_options(reader.section("status"), &config->status);
}

namespace {

const char* state_name(int8_t state) {
  switch (state) {
    case process_status_t::OK:
      return "ok";
    case process_status_t::DEGRADED:
      return "degraded";
    case process_status_t::ERROR:
      return "error";
    default:
      return "invalid";
  }
}

}  // namespace

void StatusTable::update(const process_status_t& status, int64_t receive_utime) {
  entries_[{status.process, status.pid}] = Entry{status, receive_utime};
}

bool StatusTable::is_stale(const Entry& entry, int64_t now_utime) const {
  return now_utime - entry.receive_utime > stale_after_us_;
}

std::string StatusTable::render_text(int64_t now_utime) const {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof(line), "%-22s %7s %-9s %9s %9s %8s %7s %9s %9s  %s\n", "PROCESS", "PID", "STATE", "IN",
                "OUT", "DECODE", "DROPS", "P50[ms]", "P99[ms]", "MESSAGE");
  out << line;
  for (const auto& [key, entry] : entries_) {
    const process_status_t& s = entry.status;
    const bool stale = is_stale(entry, now_utime);
    std::snprintf(line, sizeof(line), "%-22s %7d %-9s %9lld %9lld %8lld %7lld %9.3f %9.3f  %s\n", s.process.c_str(),
                  s.pid, stale ? "gone" : state_name(s.state), static_cast<long long>(s.messages_in),
                  static_cast<long long>(s.messages_out), static_cast<long long>(s.decode_errors),
                  static_cast<long long>(s.drops), s.processing_time_p50 * 1e3, s.processing_time_p99 * 1e3,
                  s.message.c_str());
    out << line;
  }
  if (entries_.empty()) {
    out << "(no PROCESS_STATUS received yet)\n";
  }
  return out.str();
}

std::string StatusTable::render_json(int64_t now_utime) const {
  nlohmann::json processes = nlohmann::json::array();
  for (const auto& [key, entry] : entries_) {
    const process_status_t& s = entry.status;
    nlohmann::json channels = nlohmann::json::array();
    for (const channel_stats_t& c : s.channels) {
      channels.push_back({{"channel", c.channel},
                          {"direction", c.direction == channel_stats_t::SUBSCRIBED ? "in" : "out"},
                          {"messages", c.messages},
                          {"decode_errors", c.decode_errors},
                          {"drops", c.drops}});
    }
    processes.push_back({{"process", s.process},
                         {"pid", s.pid},
                         {"state", is_stale(entry, now_utime) ? "gone" : state_name(s.state)},
                         {"message", s.message},
                         {"uptime", s.uptime},
                         {"messages_in", s.messages_in},
                         {"messages_out", s.messages_out},
                         {"decode_errors", s.decode_errors},
                         {"drops", s.drops},
                         {"processing_time_p50", s.processing_time_p50},
                         {"processing_time_p99", s.processing_time_p99},
                         {"channels", channels}});
  }
  // Names and messages come off the bus: invalid UTF-8 is replaced, not an exception.
  return nlohmann::json{{"processes", processes}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::vector<std::string> StatusTable::check_expected(const std::vector<std::string>& names, int64_t now_utime) const {
  std::vector<std::string> problems;
  for (const std::string& name : names) {
    const Entry* newest = nullptr;
    for (const auto& [key, entry] : entries_) {
      if (key.first == name && (newest == nullptr || entry.receive_utime > newest->receive_utime)) {
        newest = &entry;
      }
    }
    if (newest == nullptr) {
      problems.push_back(name + ": no status received");
    } else if (is_stale(*newest, now_utime)) {
      problems.push_back(name + ": no status for " + std::to_string((now_utime - newest->receive_utime) / 1000000) +
                         " s");
    } else if (newest->status.state == process_status_t::ERROR) {
      problems.push_back(name + ": error: " + newest->status.message);
    }
  }
  return problems;
}

}  // namespace slamer

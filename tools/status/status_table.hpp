// The latest PROCESS_STATUS of every process seen, rendered as a terminal table
// or JSON, and checked against the processes a script expects to be healthy.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/process/process_options.hpp"
#include "slamer/process_status_t.hpp"

namespace slamer {

struct StatusMonitorOptions {
  std::string channel = "PROCESS_STATUS";
  double stale_after = 3.0;  // [s] without a status before a process counts as gone
};
void read_options(const ConfigReader& reader, StatusMonitorOptions* options);

// The whole config file of slamer-status (config/slamer-status.yaml).
struct StatusProcessConfig {
  ProcessOptions process;
  StatusMonitorOptions status;
};
void read_options(const ConfigReader& reader, StatusProcessConfig* config);

class StatusTable {
 public:
  explicit StatusTable(double stale_after_s) : stale_after_us_(static_cast<int64_t>(stale_after_s * 1e6)) {}

  // Keyed by (process, pid), so a restarted process shows as a new row.
  void update(const process_status_t& status, int64_t receive_utime);

  std::string render_text(int64_t now_utime) const;
  std::string render_json(int64_t now_utime) const;

  // Problems with the expected processes (absent, stale, or in ERROR), one per
  // entry; empty when all of them report OK or DEGRADED recently.
  std::vector<std::string> check_expected(const std::vector<std::string>& names, int64_t now_utime) const;

 private:
  struct Entry {
    process_status_t status;
    int64_t receive_utime = 0;
  };
  bool is_stale(const Entry& entry, int64_t now_utime) const;

  int64_t stale_after_us_;
  std::map<std::pair<std::string, int32_t>, Entry> entries_;
};

}  // namespace slamer

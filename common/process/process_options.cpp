#include "common/process/process_options.hpp"

namespace slamer {

void read_options(const ConfigReader& reader, ProcessOptions* options) {
  reader.read("status_channel", &options->status_channel);
  reader.read("status_period", &options->status_period, in_range(0.01, 3600.0));
  reader.read("error_log_period", &options->error_log_period, in_range(0.01, 3600.0));
  if (options->status_channel.empty()) {
    reader.fail("status_channel", "must not be empty");
  }
}

}  // namespace slamer

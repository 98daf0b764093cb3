// What every program's main() shares: the common command line (--config,
// --lcm-url, --help, and for programs that replay, --replay IN --out OUT),
// the config loading, the choice of bus, and one-line errors with exit codes
// (usage 2, config and runtime 1).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "common/config/config_reader.hpp"
#include "common/process/bus.hpp"
#include "common/process/command_line.hpp"

namespace slamer {

// The program's config from --config FILE, or its defaults without --config.
template <class Config>
Config load_config(const CommandLine& command_line) {
  Config config;
  if (command_line.has("config")) {
    config = load_options<Config>(command_line.get("config"));
  }
  return config;
}

// Declares --replay IN.lcm and --out OUT.lcm (offline: the LogBus).
void add_replay_options(CommandLine& command_line, const std::string& what_is_added);

// The bus the command line asks for: with --replay/--out a LogBus, else a
// live LcmBus on --lcm-url. Throws CommandLineError if only one of
// --replay/--out is given, std::runtime_error if the bus cannot be opened.
std::unique_ptr<Bus> open_bus(const CommandLine& command_line, const std::string& program,
                              const ProcessOptions& options);

// Runs a program's body with the common command line declared. `declare`
// adds program-specific options.
int process_main(int argc, const char* const argv[], const std::string& program, const std::string& summary,
                 const std::function<void(CommandLine&)>& declare, const std::function<int(const CommandLine&)>& body);

}  // namespace slamer

#include "common/process/process_main.hpp"

#include <iostream>

#include "common/process/lcm_bus.hpp"
#include "common/process/log_bus.hpp"

namespace slamer {

void add_replay_options(CommandLine& command_line, const std::string& what_is_added) {
  command_line.add_option("replay", "IN.lcm", "offline: read this log instead of LCM");
  command_line.add_option("out", "OUT.lcm", "offline: write the log with " + what_is_added + " added here");
}

std::unique_ptr<Bus> open_bus(const CommandLine& command_line, const std::string& program,
                              const ProcessOptions& options) {
  const bool replay = command_line.declares("replay") && command_line.has("replay");
  if (command_line.declares("replay") && replay != command_line.has("out")) {
    throw CommandLineError("--replay and --out go together");
  }
  if (replay) {
    return std::make_unique<LogBus>(program, command_line.get("replay"), command_line.get("out"), options);
  }
  return std::make_unique<LcmBus>(program, command_line.get("lcm-url"), options);
}

int process_main(int argc, const char* const argv[], const std::string& program, const std::string& summary,
                 const std::function<void(CommandLine&)>& declare, const std::function<int(const CommandLine&)>& body) {
  CommandLine command_line(program, summary);
  command_line.add_option("config", "FILE", "YAML configuration file");
  command_line.add_option("lcm-url", "URL", "LCM URL, e.g. udpm://239.255.76.67:7667?ttl=0 (default: LCM's default)");
  try {
    declare(command_line);
    if (!command_line.parse(argc, argv, std::cout)) {
      return 0;
    }
  } catch (const CommandLineError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  }
  try {
    return body(command_line);
  } catch (const ConfigError& e) {
    std::cerr << program << ": config error: " << e.what() << "\n";
  } catch (const CommandLineError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
  }
  return 1;
}

}  // namespace slamer

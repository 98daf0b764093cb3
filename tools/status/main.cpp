// slamer-status: shows the health of every running process from PROCESS_STATUS.
#include <unistd.h>

#include <iostream>
#include <sstream>

#include "common/process/lcm_bus.hpp"
#include "common/process/process_main.hpp"
#include "tools/status/status_table.hpp"

namespace {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) {
      items.push_back(item);
    }
  }
  return items;
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-status",
      "Shows the state, message counters, decode errors and processing time of every SLAMER process\n"
      "from their PROCESS_STATUS messages. With --once it listens for a while, prints once and exits\n"
      "(status 1 if a process named in --expect is missing, gone or in error): for scripts and tests.",
      [](slamer::CommandLine& cli) {
        cli.add_option("once", "SECONDS", "listen this long, print once and exit");
        cli.add_option("expect", "A,B,...", "with --once: process names that must be alive and not in error");
        cli.add_flag("json", "print JSON instead of a table");
      },
      [](const slamer::CommandLine& cli) {
        const auto config = slamer::load_config<slamer::StatusProcessConfig>(cli);
        const bool once = cli.has("once");
        const double once_s = once ? cli.get_double("once") : 0.0;
        if (once && once_s <= 0.0) {
          throw slamer::CommandLineError("option '--once': expected a positive number of seconds");
        }
        const std::vector<std::string> expected = split_commas(cli.get("expect"));
        const bool json = cli.has("json");
        const bool terminal = !once && isatty(STDOUT_FILENO) != 0;

        slamer::LcmBus process("slamer-status", cli.get("lcm-url"), config.process);
        slamer::StatusTable table(config.status.stale_after);
        process.subscribe<slamer::process_status_t>(
            config.status.channel, [&](const slamer::process_status_t& status, const slamer::ReceiveInfo& info) {
              table.update(status, info.receive_utime);
            });
        auto print = [&] {
          const int64_t now = slamer::now_utime();
          std::cout << (terminal ? "\033[H\033[2J" : "") << (json ? table.render_json(now) : table.render_text(now))
                    << std::flush;
        };
        if (once) {
          process.every(once_s, [&] { process.stop(); });
        } else {
          process.every(1.0, print);
        }
        const int code = process.run();
        if (!once) {
          return code;
        }
        print();
        const std::vector<std::string> problems = table.check_expected(expected, slamer::now_utime());
        for (const std::string& problem : problems) {
          std::cerr << "slamer-status: " << problem << "\n";
        }
        return problems.empty() ? code : 1;
      });
}

// slamer-launch: runs the processes a launch file lists (config/launch/*.yaml,
// format in launch_file.hpp) under Debian's supervisor, or with --check
// validates the file and every config it names without starting anything.
#include <linux/limits.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "common/process/command_line.hpp"
#include "tools/launch/launch_check.hpp"
#include "tools/launch/launcher.hpp"

namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, separator);) {
    if (!item.empty()) {
      items.push_back(item);
    }
  }
  return items;
}

// Bare program names: beside slamer-launch first (the build's bin/ or the
// installed bin/), then PATH.
std::vector<std::string> search_dirs() {
  std::vector<std::string> dirs;
  char self[PATH_MAX] = {};
  if (readlink("/proc/self/exe", self, sizeof self - 1) > 0) {
    dirs.push_back(std::filesystem::path(self).parent_path().string());
  }
  const char* path = std::getenv("PATH");
  for (const std::string& dir : split(path != nullptr ? path : "/usr/bin:/bin", ':')) {
    dirs.push_back(dir);
  }
  return dirs;
}

}  // namespace

int main(int argc, char** argv) {
  slamer::CommandLine cli(
      "slamer-launch",
      "Starts the processes a launch file lists under supervisor (supervisord runs as a child): one LCM URL\n"
      "for all, groups started in order, respawn with backoff, NAME.log per process in the log directory,\n"
      "a live status table from PROCESS_STATUS on a terminal; Ctrl-C or SIGTERM stops them in reverse\n"
      "order and exits 0. --check validates the file and every config it names (one line per problem).");
  cli.set_positional("FILE", "launch file (config/launch/*.yaml)", 1, 1);
  cli.add_flag("check", "validate FILE and what it names, start nothing; exit 1 on any problem");
  cli.add_option("lcm-url", "URL", "LCM URL for every process (overrides the file's lcm_url)");
  cli.add_option("log-dir", "DIR", "per-process logs here (overrides the file's log_dir)");
  cli.add_option("run-dir", "DIR", "supervisord.conf and its socket here (overrides the file's run_dir)");
  cli.add_option("state-dir", "DIR", "${state_dir} of the file's args (overrides the file's state_dir)");
  cli.add_option("enable", "A,B,...", "also start these processes the file lists with enabled: false");
  cli.add_option("disable", "A,B,...", "do not start these");
  try {
    if (!cli.parse(argc, argv, std::cout)) {
      return 0;
    }
  } catch (const slamer::CommandLineError& e) {
    std::cerr << "slamer-launch: error: " << e.what() << "\n";
    return 2;
  }
  const std::string file = cli.positional().at(0);
  if (cli.has("check")) {
    const std::vector<std::string> problems = slamer::launch::check_launch_file(file, search_dirs());
    for (const std::string& problem : problems) {
      std::cout << problem << "\n";
    }
    if (problems.empty()) {
      std::cout << file << ": OK\n";
    }
    return problems.empty() ? 0 : 1;
  }
  slamer::launch::LaunchRequest request;
  request.file = file;
  request.lcm_url_given = cli.has("lcm-url");
  request.lcm_url = cli.get("lcm-url");
  request.log_dir = cli.get("log-dir");
  request.run_dir = cli.get("run-dir");
  request.state_dir = cli.get("state-dir");
  request.enable = split(cli.get("enable"), ',');
  request.disable = split(cli.get("disable"), ',');
  request.search_dirs = search_dirs();
  try {
    return slamer::launch::run_launch(request);
  } catch (const std::exception& e) {
    std::cerr << "slamer-launch: error: " << e.what() << "\n";
  }
  return 1;
}

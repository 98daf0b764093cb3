#include "tools/launch/launch_check.hpp"

#include <unistd.h>

#include <filesystem>
#include <functional>
#include <map>

#include "common/config/config_reader.hpp"
#include "common/map/semantic_map.hpp"
#include "common/robot/robot_options.hpp"
#include "drivers/urg/urg_options.hpp"
#include "drivers/wheels/wheels_options.hpp"
#include "localizer/localizer_config.hpp"
#include "recognizer/recognizer_config.hpp"
#include "tools/launch/program_help.hpp"
#include "tools/sim/sim_config.hpp"
#include "tools/sim/world.hpp"
#include "tools/status/status_table.hpp"

namespace slamer::launch {
namespace {

namespace fs = std::filesystem;

using Checker = std::function<void(const std::string& config, const std::vector<std::string>& args,
                                   const std::string& working_dir)>;

template <class Config>
Config load_or_default(const std::string& config) {
  return config.empty() ? Config{} : load_options<Config>(config);
}

std::string arg_path(const std::vector<std::string>& args, const std::string& flag, const std::string& working_dir) {
  const std::string value = flag_value(args, flag);
  if (value.empty() || fs::path(value).is_absolute()) {
    return value;
  }
  return (fs::path(working_dir) / value).lexically_normal().string();
}

void check_localizer(const std::string& config, const std::vector<std::string>& args, const std::string& dir) {
  auto c = load_or_default<LocalizerProcessConfig>(config);
  if (has_flag(args, "--map")) {
    c.map = arg_path(args, "--map", dir);
  }
  if (has_flag(args, "--robot")) {
    c.robot = arg_path(args, "--robot", dir);
  }
  if (c.map.empty()) {
    throw ConfigError("slamer-localizer: no map: set 'map' in its config or pass --map in args");
  }
  load_semantic_map(c.map);
  if (!c.robot.empty()) {
    load_options<RobotOptions>(c.robot);
  }
}

void check_sim(const std::string& config, const std::vector<std::string>& args, const std::string& dir) {
  load_or_default<SimProcessConfig>(config);
  const std::string world_path = arg_path(args, "--world", dir);
  if (world_path.empty()) {
    throw ConfigError("slamer-sim: --world FILE is required in args");
  }
  const auto world = load_options<WorldOptions>(world_path);
  load_options<RobotOptions>(world.robot_path);
  const TrueWorld truth(load_semantic_map(world.map_path), world, world_path);
}

const std::map<std::string, Checker>& checkers() {
  static const std::map<std::string, Checker> table = {
      {"slamer-localizer", check_localizer},
      {"slamer-recognizer", [](const std::string& c, const std::vector<std::string>&,
                               const std::string&) { load_or_default<RecognizerProcessConfig>(c); }},
      {"slamer-urg", [](const std::string& c, const std::vector<std::string>&,
                        const std::string&) { load_or_default<urg::UrgProcessConfig>(c); }},
      {"slamer-wheels", [](const std::string& c, const std::vector<std::string>&,
                           const std::string&) { load_or_default<WheelsConfig>(c); }},
      {"slamer-sim", check_sim},
      {"slamer-status", [](const std::string& c, const std::vector<std::string>&,
                           const std::string&) { load_or_default<StatusProcessConfig>(c); }},
  };
  return table;
}

}  // namespace

std::string find_program(const std::string& program, const std::string& base_dir,
                         const std::vector<std::string>& search_dirs) {
  auto executable = [](const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error) && access(path.c_str(), X_OK) == 0;
  };
  if (program.find('/') == std::string::npos) {
    for (const std::string& dir : search_dirs) {
      if (!dir.empty() && executable(fs::path(dir) / program)) {
        return fs::absolute(fs::path(dir) / program).lexically_normal().string();
      }
    }
    return "";
  }
  const fs::path path = fs::path(program).is_absolute() ? fs::path(program) : fs::path(base_dir) / program;
  return executable(path) ? fs::absolute(path).lexically_normal().string() : "";
}

std::vector<std::string> checked_programs() {
  std::vector<std::string> names;
  for (const auto& [name, checker] : checkers()) {
    names.push_back(name);
  }
  return names;
}

std::string check_program(const std::string& program, const std::string& config, const std::vector<std::string>& args,
                          const std::string& working_dir, bool* known) {
  const auto checker = checkers().find(fs::path(program).filename().string());
  *known = checker != checkers().end();
  if (!*known) {
    return "";
  }
  try {
    checker->second(config, args, working_dir);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> check_launch_file(const std::string& path, const std::vector<std::string>& search_dirs) {
  std::vector<std::string> problems;
  const LaunchFile file = read_launch_file(path, &problems);
  for (const LaunchProcess& p : file.processes) {
    if (p.program.empty()) {
      continue;
    }
    const std::string where_program = p.where.at("program");
    const std::string program_path = find_program(p.program, file.directory, search_dirs);
    if (program_path.empty()) {
      problems.push_back(
          where_program + ": program '" + p.program + "' not found" +
          (p.program.find('/') == std::string::npos ? " beside slamer-launch or in PATH" : " (or not executable)"));
    } else {
      // The options passed must be ones the program lists in its --help.
      // (--config: a program slamer-launch can check takes it; for others the config is reported below.)
      std::vector<std::string> passed = p.args;
      if (p.lcm && !file.lcm_url.empty()) {
        passed.push_back("--lcm-url");
      }
      for (const std::string& option : unlisted_options(passed, program_help(program_path))) {
        problems.push_back(p.where.at(option == "--lcm-url" ? "program" : "args") + ": '" + p.program +
                           "' does not list " + option + " in its --help" +
                           (option == "--lcm-url" ? " (lcm: false if it is not on LCM)" : ""));
      }
    }
    std::vector<std::string> args;
    try {
      for (const std::string& arg : p.args) {
        args.push_back(expand(arg, Directories{"", "LOG_DIR", "RUN_DIR", "STATE_DIR"}));
      }
    } catch (const std::invalid_argument&) {
      continue;  // reported by read_launch_file
    }
    std::error_code error;
    if (!p.config.empty() && !fs::is_regular_file(p.config, error)) {
      problems.push_back(p.where.at("config") + ": '" + p.config + "' does not exist");
      continue;
    }
    bool known = false;
    const std::string problem = check_program(p.program, p.config, args, file.directory, &known);
    if (!known && !p.config.empty()) {
      std::string list;
      for (const std::string& name : checked_programs()) {
        list += (list.empty() ? "" : ", ") + name;
      }
      problems.push_back(p.where.at("config") + ": slamer-launch cannot check a config of '" + p.program +
                         "' (it knows " + list + ")");
    } else if (!problem.empty()) {
      problems.push_back(problem + " (process '" + p.name + "', " + p.where.at(p.config.empty() ? "args" : "config") +
                         ")");
    }
  }
  return problems;
}

}  // namespace slamer::launch

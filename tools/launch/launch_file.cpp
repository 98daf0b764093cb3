#include "tools/launch/launch_file.hpp"

#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "common/config/config_reader.hpp"

namespace slamer::launch {
namespace {

const std::set<std::string> kTopKeys = {"lcm_url", "log_dir", "run_dir", "state_dir", "processes"};
const std::set<std::string> kProcessKeys = {"name",  "program",       "config",        "args",
                                            "group", "enabled",       "respawn",       "required",
                                            "lcm",   "start_seconds", "start_retries", "stop_timeout"};

template <class F>
void attempt(std::vector<std::string>* problems, F&& read) {
  try {
    read();
  } catch (const ConfigError& e) {
    problems->push_back(e.what());
  }
}

std::string known_list(const std::set<std::string>& keys) {
  std::string text;
  for (const std::string& key : keys) {
    text += (text.empty() ? "" : ", ") + key;
  }
  return text;
}

void check_keys(const ConfigReader& reader, const std::set<std::string>& known, std::vector<std::string>* problems) {
  for (const std::string& key : reader.keys()) {
    if (known.count(key) == 0) {
      attempt(problems, [&] { reader.fail(key, "unknown key (known: " + known_list(known) + ")"); });
    }
  }
}

// "FILE:LINE: key 'processes[i].KEY'" of a process's key, for later messages.
std::string where_of(const ConfigReader& reader, const std::string& key) {
  try {
    reader.fail(key, "");
  } catch (const ConfigError& e) {
    std::string text = e.what();
    if (text.size() >= 2 && text.compare(text.size() - 2, 2, ": ") == 0) {
      text.resize(text.size() - 2);
    }
    return text;
  }
  return reader.source();
}

bool valid_name(const std::string& name) {
  if (name.empty()) {
    return false;
  }
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) {
      return false;
    }
  }
  return true;
}

// Supervisor's INI reader ends a value at whitespace followed by ';' or '#',
// and takes a line break as a continuation: such arguments cannot be passed.
std::string argument_problem(const std::string& arg) {
  for (std::size_t i = 0; i < arg.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(arg[i]);
    if (c < 0x20 || c == 0x7f) {
      return "control characters (a line break, a tab) cannot be passed through supervisor";
    }
    if ((c == ' ') && i + 1 < arg.size() && (arg[i + 1] == ';' || arg[i + 1] == '#')) {
      return "' ;' and ' #' start a comment in supervisor's configuration";
    }
  }
  if (arg == "--config" || arg.rfind("--config=", 0) == 0) {
    return "give the config file as the process's 'config' key (it is checked), not in args";
  }
  if (arg == "--lcm-url" || arg.rfind("--lcm-url=", 0) == 0) {
    return "every process gets the launch file's lcm_url; set 'lcm_url' at the top";
  }
  return "";
}

LaunchProcess read_process(const ConfigReader& reader, const std::string& directory,
                           std::vector<std::string>* problems) {
  LaunchProcess p;
  check_keys(reader, kProcessKeys, problems);
  for (const char* key : {"name", "program", "config", "args"}) {
    p.where[key] = where_of(reader, key);
  }
  attempt(problems, [&] {
    reader.require("name");
    reader.read("name", &p.name);
    if (!valid_name(p.name)) {
      reader.fail("name", "'" + p.name + "' is not a name of letters, digits, '_' and '-'");
    }
  });
  attempt(problems, [&] {
    reader.require("program");
    reader.read("program", &p.program);
    if (p.program.empty() || p.program.find_first_of(" \t\n") != std::string::npos) {
      reader.fail("program", "expected a program name or path without spaces, got '" + p.program + "'");
    }
  });
  attempt(problems, [&] {
    reader.read("config", &p.config);
    if (!p.config.empty() && std::filesystem::path(p.config).is_relative()) {
      // Absolute: the processes run in the launch file's directory, not where slamer-launch started.
      p.config = std::filesystem::absolute(std::filesystem::path(directory) / p.config).lexically_normal().string();
    }
  });
  attempt(problems, [&] {
    reader.read("args", &p.args);
    for (std::size_t i = 0; i < p.args.size(); ++i) {
      const std::string problem = argument_problem(p.args[i]);
      if (!problem.empty()) {
        reader.fail("args", "argument " + std::to_string(i + 1) + " '" + p.args[i] + "': " + problem);
      }
      try {
        expand(p.args[i], Directories{});
      } catch (const std::invalid_argument& e) {
        reader.fail("args", "argument " + std::to_string(i + 1) + ": " + e.what());
      }
    }
  });
  attempt(problems, [&] { reader.read("group", &p.group, in_range(0, 99)); });
  attempt(problems, [&] { reader.read("enabled", &p.enabled); });
  attempt(problems, [&] { reader.read("respawn", &p.respawn); });
  attempt(problems, [&] { reader.read("required", &p.required); });
  attempt(problems, [&] { reader.read("lcm", &p.lcm); });
  attempt(problems, [&] { reader.read("start_seconds", &p.start_seconds, in_range(0, 3600)); });
  attempt(problems, [&] { reader.read("start_retries", &p.start_retries, in_range(0, 1000)); });
  attempt(problems, [&] { reader.read("stop_timeout", &p.stop_timeout, in_range(1, 3600)); });
  return p;
}

LaunchFile read_reader(const ConfigReader& reader, std::vector<std::string>* problems) {
  LaunchFile file;
  file.source = reader.source();
  file.directory = reader.directory().empty() ? "." : reader.directory();
  check_keys(reader, kTopKeys, problems);
  attempt(problems, [&] {
    reader.read("lcm_url", &file.lcm_url);
    if (file.lcm_url.find_first_of(" \t\n;#%'\"") != std::string::npos) {
      reader.fail("lcm_url", "'" + file.lcm_url + "' has a space, quote, ';', '#' or '%'");
    }
  });
  attempt(problems, [&] { reader.read("log_dir", &file.log_dir); });
  attempt(problems, [&] { reader.read("run_dir", &file.run_dir); });
  attempt(problems, [&] { reader.read("state_dir", &file.state_dir); });
  std::vector<ConfigReader> entries;
  attempt(problems, [&] {
    reader.require("processes");
    entries = reader.list("processes");
  });
  std::map<std::string, std::string> first_seen;
  int enabled = 0;
  for (const ConfigReader& entry : entries) {
    LaunchProcess p = read_process(entry, file.directory, problems);
    if (!p.name.empty()) {
      const auto inserted = first_seen.emplace(p.name, p.where["name"]);
      if (!inserted.second) {
        const std::string first = inserted.first->second;
        attempt(problems, [&] { entry.fail("name", "duplicate name '" + p.name + "' (first at " + first + ")"); });
      }
    }
    enabled += p.enabled ? 1 : 0;
    file.processes.push_back(std::move(p));
  }
  if (!entries.empty() && enabled == 0) {
    attempt(problems, [&] { reader.fail("processes", "no process is enabled"); });
  } else if (entries.empty() && reader.has("processes")) {
    attempt(problems, [&] { reader.fail("processes", "the list is empty"); });
  }
  return file;
}

}  // namespace

LaunchFile read_launch_file(const std::string& path, std::vector<std::string>* problems) {
  try {
    return read_reader(ConfigReader::from_file(path), problems);
  } catch (const ConfigError& e) {
    problems->push_back(e.what());
  }
  LaunchFile file;
  file.source = path;
  return file;
}

LaunchFile parse_launch_file(const std::string& yaml_text, const std::string& source_name,
                             std::vector<std::string>* problems) {
  try {
    return read_reader(ConfigReader::from_string(yaml_text, source_name), problems);
  } catch (const ConfigError& e) {
    problems->push_back(e.what());
  }
  LaunchFile file;
  file.source = source_name;
  return file;
}

std::string flag_value(const std::vector<std::string>& args, const std::string& flag) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == flag && i + 1 < args.size()) {
      return args[i + 1];
    }
    if (args[i].rfind(flag + "=", 0) == 0) {
      return args[i].substr(flag.size() + 1);
    }
  }
  return "";
}

bool has_flag(const std::vector<std::string>& args, const std::string& flag) {
  for (const std::string& arg : args) {
    if (arg == flag || arg.rfind(flag + "=", 0) == 0) {
      return true;
    }
  }
  return false;
}

std::string expand(const std::string& text, const Directories& dirs) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t open = text.find("${", i);
    if (open == std::string::npos) {
      out += text.substr(i);
      break;
    }
    const std::size_t close = text.find('}', open);
    const std::string name = close == std::string::npos ? "" : text.substr(open + 2, close - open - 2);
    out += text.substr(i, open - i);
    if (name == "log_dir") {
      out += dirs.log_dir;
    } else if (name == "run_dir") {
      out += dirs.run_dir;
    } else if (name == "state_dir") {
      out += dirs.state_dir;
    } else {
      throw std::invalid_argument("unknown '${" + name + (close == std::string::npos ? "" : "}") +
                                  "' (only ${log_dir}, ${run_dir} and ${state_dir} expand)");
    }
    i = close + 1;
  }
  return out;
}

}  // namespace slamer::launch

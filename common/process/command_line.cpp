#include "common/process/command_line.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace slamer {

CommandLine::CommandLine(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary)) {
  add_flag("help", "show this help and exit");
}

void CommandLine::add_option(const std::string& name, const std::string& value_name, const std::string& help,
                             const std::string& default_value) {
  if (declared_.count(name) == 0) {
    order_.push_back(name);
  }
  declared_[name] = Declared{true, value_name, help, default_value, 1};
}

void CommandLine::add_multi_option(const std::string& name, std::size_t count, const std::string& value_names,
                                   const std::string& help) {
  add_option(name, value_names, help);
  declared_[name].value_count = count;
}

void CommandLine::add_flag(const std::string& name, const std::string& help) {
  if (declared_.count(name) == 0) {
    order_.push_back(name);
  }
  declared_[name] = Declared{false, "", help, "", 0};
}

void CommandLine::set_positional(const std::string& name, const std::string& help, std::size_t min_count,
                                 std::size_t max_count) {
  positional_name_ = name;
  positional_help_ = help;
  positional_min_ = min_count;
  positional_max_ = max_count;
}

const CommandLine::Declared& CommandLine::declared(const std::string& name) const {
  const auto it = declared_.find(name);
  if (it == declared_.end()) {
    throw std::logic_error("option --" + name + " was never declared");
  }
  return it->second;
}

bool CommandLine::parse(int argc, const char* const argv[], std::ostream& help_out) {
  given_.clear();
  positional_.clear();
  bool only_positional = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (only_positional || arg.size() < 2 || arg.rfind("--", 0) != 0) {
      if (!only_positional && arg.size() > 1 && arg[0] == '-') {
        throw CommandLineError("unknown option '" + arg + "' (options are written --name; see --help)");
      }
      positional_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      only_positional = true;
      continue;
    }
    const std::size_t equals = arg.find('=');
    const std::string name = arg.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
    const auto it = declared_.find(name);
    if (it == declared_.end()) {
      throw CommandLineError("unknown option '--" + name + "' (see --help)");
    }
    if (!it->second.takes_value) {
      if (equals != std::string::npos) {
        throw CommandLineError("option '--" + name + "' takes no value");
      }
      given_[name] = "1";
    } else if (it->second.value_count > 1) {
      if (equals != std::string::npos || i + static_cast<int>(it->second.value_count) >= argc) {
        throw CommandLineError("option '--" + name + "' needs " + std::to_string(it->second.value_count) + " values " +
                               it->second.value_name);
      }
      std::string values;
      for (std::size_t k = 0; k < it->second.value_count; ++k) {
        values += (k == 0 ? "" : " ") + std::string(argv[++i]);
      }
      given_[name] = values;
    } else if (equals != std::string::npos) {
      given_[name] = arg.substr(equals + 1);
    } else if (i + 1 < argc) {
      given_[name] = argv[++i];
    } else {
      throw CommandLineError("option '--" + name + "' needs a value " + it->second.value_name);
    }
  }
  if (given_.count("help") != 0) {
    help_out << usage();
    return false;
  }
  if (positional_.size() < positional_min_ || positional_.size() > positional_max_) {
    if (positional_max_ == 0) {
      throw CommandLineError("unexpected argument '" + positional_.front() + "' (see --help)");
    }
    throw CommandLineError("expected " +
                           (positional_min_ == positional_max_
                                ? std::to_string(positional_min_)
                                : std::to_string(positional_min_) + " to " + std::to_string(positional_max_)) +
                           " " + positional_name_ + " argument(s), got " + std::to_string(positional_.size()));
  }
  return true;
}

bool CommandLine::has(const std::string& name) const {
  declared(name);
  return given_.count(name) != 0;
}

std::string CommandLine::get(const std::string& name) const {
  const Declared& option = declared(name);
  const auto it = given_.find(name);
  return it == given_.end() ? option.default_value : it->second;
}

double CommandLine::get_double(const std::string& name) const {
  const std::string text = get(name);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw CommandLineError("option '--" + name + "': expected a number, got '" + text + "'");
  }
  return value;
}

int64_t CommandLine::get_int(const std::string& name) const {
  const std::string text = get(name);
  int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw CommandLineError("option '--" + name + "': expected an integer, got '" + text + "'");
  }
  return value;
}

std::vector<double> CommandLine::get_doubles(const std::string& name) const {
  std::istringstream words(get(name));
  std::vector<double> values;
  for (std::string word; words >> word;) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
      throw CommandLineError("option '--" + name + "': expected numbers " + declared(name).value_name + ", got '" +
                             word + "'");
    }
    values.push_back(value);
  }
  return values;
}

std::string CommandLine::usage() const {
  std::ostringstream out;
  out << "usage: " << program_ << " [options]";
  if (positional_max_ > 0) {
    out << (positional_min_ == 0 ? " [" : " ") << positional_name_ << (positional_max_ > 1 ? "..." : "")
        << (positional_min_ == 0 ? "]" : "");
  }
  out << "\n\n" << summary_ << "\n\noptions:\n";
  for (const std::string& name : order_) {
    const Declared& option = declared_.at(name);
    std::string left = "  --" + name + (option.takes_value ? " " + option.value_name : "");
    if (left.size() < 26) {
      left.resize(26, ' ');
    } else {
      left += "\n" + std::string(26, ' ');
    }
    out << left << option.help;
    if (!option.default_value.empty()) {
      out << " (default: " << option.default_value << ")";
    }
    out << "\n";
  }
  if (positional_max_ > 0) {
    out << "\n  " << positional_name_ << ": " << positional_help_ << "\n";
  }
  return out.str();
}

}  // namespace slamer

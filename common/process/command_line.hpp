// Command-line parsing shared by every program: --name VALUE, --name=VALUE,
// flags, positional arguments, and --help generated from the declarations.
// Errors are CommandLineError with a one-line message naming the option.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace slamer {

class CommandLineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CommandLine {
 public:
  CommandLine(std::string program, std::string summary);

  void add_option(const std::string& name, const std::string& value_name, const std::string& help,
                  const std::string& default_value = "");
  // An option followed by exactly `count` values (--initial-pose X Y THETA); read with get_doubles().
  void add_multi_option(const std::string& name, std::size_t count, const std::string& value_names,
                        const std::string& help);
  void add_flag(const std::string& name, const std::string& help);
  // Positional arguments: name and help for --help; min/max how many are accepted.
  void set_positional(const std::string& name, const std::string& help, std::size_t min_count, std::size_t max_count);

  // Returns false when --help was given (the usage has been written to help_out).
  bool parse(int argc, const char* const argv[], std::ostream& help_out);

  bool declares(const std::string& name) const { return declared_.count(name) != 0; }
  bool has(const std::string& name) const;         // given on the command line
  std::string get(const std::string& name) const;  // value given, else the default
  double get_double(const std::string& name) const;
  int64_t get_int(const std::string& name) const;
  std::vector<double> get_doubles(const std::string& name) const;  // the values of a multi-value option
  const std::vector<std::string>& positional() const { return positional_; }
  const std::string& program() const { return program_; }
  std::string usage() const;

 private:
  struct Declared {
    bool takes_value = true;
    std::string value_name;
    std::string help;
    std::string default_value;
    std::size_t value_count = 1;
  };
  const Declared& declared(const std::string& name) const;

  std::string program_;
  std::string summary_;
  std::vector<std::string> order_;
  std::map<std::string, Declared> declared_;
  std::map<std::string, std::string> given_;
  std::string positional_name_;
  std::string positional_help_;
  std::size_t positional_min_ = 0;
  std::size_t positional_max_ = 0;
  std::vector<std::string> positional_;
};

}  // namespace slamer

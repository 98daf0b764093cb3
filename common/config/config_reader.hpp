// Strict reader of YAML option files.
//
// Every component has one Options struct holding its defaults and a
//   void read_options(const ConfigReader& reader, FooOptions* options);
// that reads each key it knows. load_options<FooOptions>(path) then rejects any
// key nobody read, so a misspelt key is an error, not a silently ignored one.
// Every error is one line: "FILE:LINE: key 'a.b': problem".
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace slamer {

// Always one line: control characters in the message (from a value, a key,
// a file name or the YAML parser) are shown escaped.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(const std::string& message);
};

// Which numbers a key accepts. The default accepts every finite number.
struct NumberRule {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  bool allows(double value) const;
  std::string describe() const;  // e.g. "a number > 0", "a number in [0, 1]"
};
NumberRule positive();
NumberRule non_negative();
NumberRule at_least(double min);
NumberRule in_range(double min, double max);
NumberRule probability();  // [0, 1]

class ConfigReader {
 public:
  static ConfigReader from_file(const std::string& path);
  static ConfigReader from_string(const std::string& text, const std::string& source_name);

  // Optional keys: when `key` is absent the value keeps its default.
  void read(std::string_view key, double* value, NumberRule rule = {}) const;
  void read(std::string_view key, float* value, NumberRule rule = {}) const;
  void read(std::string_view key, int* value, NumberRule rule = {}) const;
  void read(std::string_view key, std::int64_t* value, NumberRule rule = {}) const;
  void read(std::string_view key, bool* value) const;
  void read(std::string_view key, std::string* value) const;
  void read_choice(std::string_view key, std::string* value, std::initializer_list<std::string_view> choices) const;
  // exact_size 0 accepts any length.
  void read(std::string_view key, std::vector<double>* value, NumberRule rule = {}, std::size_t exact_size = 0) const;
  void read(std::string_view key, std::vector<std::string>* value) const;

  bool has(std::string_view key) const;
  // The keys of this section in file order (for tables keyed by name); reading
  // them is what marks them used.
  std::vector<std::string> keys() const;
  void require(std::string_view key) const;  // throws if absent

  // A nested mapping; an absent key gives an empty section (all defaults).
  ConfigReader section(std::string_view key) const;
  // A sequence of mappings, e.g. a class table; absent gives an empty list.
  std::vector<ConfigReader> list(std::string_view key) const;

  // For checks across keys: throws "FILE:LINE: key 'prefix.key': problem".
  [[noreturn]] void fail(std::string_view key, std::string_view problem) const;

  // Throws on the first key in the document that no read/section/list asked for.
  void check_all_keys_used() const;

  const std::string& source() const;
  // Directory of the source file ("" for strings).
  std::string directory() const;
  // A path written in the file: relative ones are relative to the file's directory.
  std::string resolve_path(const std::string& path) const;

 private:
  struct Document;
  ConfigReader(std::shared_ptr<Document> document, YAML::Node node, std::string prefix);

  YAML::Node lookup(std::string_view key) const;  // marks the key used; null node if absent
  std::string full_key(std::string_view key) const;
  std::string where(const YAML::Node& node) const;
  double read_number(std::string_view key, const YAML::Node& node, const NumberRule& rule) const;
  std::int64_t read_integer(std::string_view key, const YAML::Node& node, const NumberRule& rule) const;

  std::shared_ptr<Document> document_;
  YAML::Node node_;
  std::string prefix_;
};

// Reads `path` into a default-constructed Options with the component's
// read_options() (found by argument-dependent lookup) and rejects unknown keys.
template <class Options>
Options load_options(const std::string& path) {
  const ConfigReader reader = ConfigReader::from_file(path);
  Options options;
  read_options(reader, &options);
  reader.check_all_keys_used();
  return options;
}

template <class Options>
Options parse_options(const std::string& yaml_text, const std::string& source_name) {
  const ConfigReader reader = ConfigReader::from_string(yaml_text, source_name);
  Options options;
  read_options(reader, &options);
  reader.check_all_keys_used();
  return options;
}

}  // namespace slamer

#include "common/config/config_reader.hpp"

#include <map>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace slamer {

struct ConfigReader::Document {
  std::string source;
  std::string directory;
  YAML::Node root;
  std::set<std::string> used;            // every key asked for
  std::set<std::string> used_as_nested;  // keys read as a section or list: their children are checked too
};

namespace {

std::string format_number(double v) {
  std::ostringstream out;
  out << std::setprecision(15) << v;
  return out.str();
}

// A value quoted for an error message, with control characters escaped so the
// message stays on one line.
std::string scalar_text(const YAML::Node& node) {
  if (node.IsScalar()) {
    std::string quoted = "'";
    for (const char c : node.Scalar().substr(0, 80)) {
      if (static_cast<unsigned char>(c) < 0x20) {
        quoted += c == '\n' ? "\\n" : c == '\t' ? "\\t" : "?";
      } else {
        quoted += c;
      }
    }
    return quoted + (node.Scalar().size() > 80 ? "...'" : "'");
  }
  if (node.IsSequence()) {
    return "a list";
  }
  if (node.IsMap()) {
    return "a mapping";
  }
  return "nothing";
}

}  // namespace

ConfigError::ConfigError(const std::string& message)
    : std::runtime_error([&message] {
        std::string line;
        for (const char c : message) {
          if (c == '\n') {
            line += "\\n";
          } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
            char escaped[8];
            std::snprintf(escaped, sizeof(escaped), "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
            line += escaped;
          } else {
            line += c;
          }
        }
        return line;
      }()) {}

bool NumberRule::allows(double value) const {
  if (!std::isfinite(value)) {
    return false;
  }
  if (min_exclusive ? value <= min : value < min) {
    return false;
  }
  return max_exclusive ? value < max : value <= max;
}

std::string NumberRule::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return "a number in " + std::string(min_exclusive ? "(" : "[") + format_number(min) + ", " + format_number(max) +
           (max_exclusive ? ")" : "]");
  }
  if (has_min) {
    return "a number " + std::string(min_exclusive ? "> " : ">= ") + format_number(min);
  }
  if (has_max) {
    return "a number " + std::string(max_exclusive ? "< " : "<= ") + format_number(max);
  }
  return "a finite number";
}

NumberRule positive() {
  return {0.0, std::numeric_limits<double>::infinity(), true, false};
}
NumberRule non_negative() {
  return at_least(0.0);
}
NumberRule at_least(double min) {
  return {min, std::numeric_limits<double>::infinity(), false, false};
}
NumberRule in_range(double min, double max) {
  return {min, max, false, false};
}
NumberRule probability() {
  return in_range(0.0, 1.0);
}

namespace {

// yaml-cpp keeps both entries of a key written twice and reads the first:
// a second, different value would be ignored without a word.
void reject_duplicate_keys(const YAML::Node& node, const std::string& prefix, const std::string& source) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      reject_duplicate_keys(node[i], prefix + "[" + std::to_string(i) + "]", source);
    }
    return;
  }
  if (!node.IsMap()) {
    return;
  }
  std::map<std::string, int> first_line;
  for (const auto& entry : node) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
    const std::string full = prefix.empty() ? key : prefix + "." + key;
    const int line = entry.first.Mark().line + 1;
    if (const auto [it, inserted] = first_line.emplace(key, line); !inserted) {
      throw ConfigError(source + ":" + std::to_string(line) + ": key '" + full + "' appears twice (first on line " +
                        std::to_string(it->second) + ")");
    }
    reject_duplicate_keys(entry.second, full, source);
  }
}

}  // namespace

ConfigReader::ConfigReader(std::shared_ptr<Document> document, YAML::Node node, std::string prefix)
    : document_(std::move(document)), node_(std::move(node)), prefix_(std::move(prefix)) {}

ConfigReader ConfigReader::from_string(const std::string& text, const std::string& source_name) {
  auto document = std::make_shared<Document>();
  document->source = source_name;
  try {
    document->root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  if (document->root.IsNull()) {
    document->root = YAML::Node(YAML::NodeType::Map);  // an empty file: all defaults
  }
  if (!document->root.IsMap()) {
    throw ConfigError(source_name + ": expected a mapping of keys at the top level, got " +
                      scalar_text(document->root));
  }
  reject_duplicate_keys(document->root, "", source_name);
  return ConfigReader(document, document->root, "");
}

ConfigReader ConfigReader::from_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw ConfigError(path + ": cannot read: is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ConfigError(path + ": cannot open: " + std::strerror(errno));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  }
  ConfigReader reader = from_string(text.str(), path);
  reader.document_->directory = std::filesystem::path(path).parent_path().string();
  return reader;
}

const std::string& ConfigReader::source() const {
  return document_->source;
}
std::string ConfigReader::directory() const {
  return document_->directory;
}

std::string ConfigReader::resolve_path(const std::string& path) const {
  if (path.empty() || std::filesystem::path(path).is_absolute() || document_->directory.empty()) {
    return path;
  }
  return (std::filesystem::path(document_->directory) / path).lexically_normal().string();
}

std::string ConfigReader::full_key(std::string_view key) const {
  return prefix_ + std::string(key);
}

std::string ConfigReader::where(const YAML::Node& node) const {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) {
    return document_->source;
  }
  return document_->source + ":" + std::to_string(mark.line + 1);
}

void ConfigReader::fail(std::string_view key, std::string_view problem) const {
  const YAML::Node node = node_.IsMap() ? node_[std::string(key)] : YAML::Node();
  throw ConfigError(where(node.IsDefined() ? node : node_) + ": key '" + full_key(key) + "': " + std::string(problem));
}

YAML::Node ConfigReader::lookup(std::string_view key) const {
  document_->used.insert(full_key(key));
  if (!node_.IsMap()) {
    return YAML::Node(YAML::NodeType::Undefined);
  }
  // const access never inserts the key into the document
  const YAML::Node& map = node_;
  return map[std::string(key)];
}

bool ConfigReader::has(std::string_view key) const {
  const YAML::Node& map = node_;
  return map.IsMap() && map[std::string(key)].IsDefined();
}

std::vector<std::string> ConfigReader::keys() const {
  std::vector<std::string> names;
  if (node_.IsMap()) {
    for (const auto& entry : node_) {
      names.push_back(entry.first.as<std::string>("?"));
    }
  }
  return names;
}

void ConfigReader::require(std::string_view key) const {
  if (!has(key)) {
    fail(key, "missing (this key is required)");
  }
}

double ConfigReader::read_number(std::string_view key, const YAML::Node& node, const NumberRule& rule) const {
  double value = 0.0;
  if (!node.IsScalar()) {
    fail(key, "expected " + rule.describe() + ", got " + scalar_text(node));
  }
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected " + rule.describe() + ", got " + scalar_text(node));
  }
  if (!rule.allows(value)) {
    fail(key, "expected " + rule.describe() + ", got " + scalar_text(node));
  }
  return value;
}

std::int64_t ConfigReader::read_integer(std::string_view key, const YAML::Node& node, const NumberRule& rule) const {
  const std::string what =
      "an integer" + (rule.describe() == "a finite number" ? std::string() : " (" + rule.describe() + ")");
  std::int64_t value = 0;
  if (!node.IsScalar()) {
    fail(key, "expected " + what + ", got " + scalar_text(node));
  }
  try {
    value = node.as<std::int64_t>();
  } catch (const YAML::Exception&) {
    fail(key, "expected " + what + ", got " + scalar_text(node));
  }
  if (!rule.allows(static_cast<double>(value))) {
    fail(key, "expected " + what + ", got " + scalar_text(node));
  }
  return value;
}

void ConfigReader::read(std::string_view key, double* value, NumberRule rule) const {
  const YAML::Node node = lookup(key);
  if (node.IsDefined()) {
    *value = read_number(key, node, rule);
  }
}

void ConfigReader::read(std::string_view key, float* value, NumberRule rule) const {
  const YAML::Node node = lookup(key);
  if (node.IsDefined()) {
    *value = static_cast<float>(read_number(key, node, rule));
  }
}

void ConfigReader::read(std::string_view key, int* value, NumberRule rule) const {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined()) {
    return;
  }
  const std::int64_t wide = read_integer(key, node, rule);
  if (wide < std::numeric_limits<int>::min() || wide > std::numeric_limits<int>::max()) {
    fail(key, "expected a 32-bit integer, got " + scalar_text(node));
  }
  *value = static_cast<int>(wide);
}

void ConfigReader::read(std::string_view key, std::int64_t* value, NumberRule rule) const {
  const YAML::Node node = lookup(key);
  if (node.IsDefined()) {
    *value = read_integer(key, node, rule);
  }
}

void ConfigReader::read(std::string_view key, bool* value) const {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined()) {
    return;
  }
  try {
    if (!node.IsScalar()) {
      throw YAML::Exception(node.Mark(), "not a scalar");
    }
    *value = node.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got " + scalar_text(node));
  }
}

void ConfigReader::read(std::string_view key, std::string* value) const {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined()) {
    return;
  }
  if (!node.IsScalar()) {
    fail(key, "expected a string, got " + scalar_text(node));
  }
  *value = node.Scalar();
}

void ConfigReader::read_choice(std::string_view key, std::string* value,
                               std::initializer_list<std::string_view> choices) const {
  std::string chosen = *value;
  read(key, &chosen);
  if (std::find(choices.begin(), choices.end(), chosen) == choices.end()) {
    std::string list;
    for (const std::string_view choice : choices) {
      list += (list.empty() ? "" : ", ") + std::string(choice);
    }
    fail(key, "expected one of " + list + ", got '" + chosen + "'");
  }
  *value = chosen;
}

void ConfigReader::read(std::string_view key, std::vector<double>* value, NumberRule rule,
                        std::size_t exact_size) const {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined()) {
    return;
  }
  if (!node.IsSequence()) {
    fail(key, "expected a list of numbers, got " + scalar_text(node));
  }
  if (exact_size != 0 && node.size() != exact_size) {
    fail(key, "expected a list of " + std::to_string(exact_size) + " numbers, got " + std::to_string(node.size()));
  }
  std::vector<double> numbers;
  for (std::size_t i = 0; i < node.size(); ++i) {
    numbers.push_back(read_number(std::string(key) + "[" + std::to_string(i) + "]", node[i], rule));
  }
  *value = std::move(numbers);
}

void ConfigReader::read(std::string_view key, std::vector<std::string>* value) const {
  const YAML::Node node = lookup(key);
  if (!node.IsDefined()) {
    return;
  }
  if (!node.IsSequence()) {
    fail(key, "expected a list of strings, got " + scalar_text(node));
  }
  std::vector<std::string> strings;
  for (std::size_t i = 0; i < node.size(); ++i) {
    if (!node[i].IsScalar()) {
      fail(std::string(key) + "[" + std::to_string(i) + "]", "expected a string, got " + scalar_text(node[i]));
    }
    strings.push_back(node[i].Scalar());
  }
  *value = std::move(strings);
}

ConfigReader ConfigReader::section(std::string_view key) const {
  const YAML::Node node = lookup(key);
  document_->used_as_nested.insert(full_key(key));
  if (!node.IsDefined() || node.IsNull()) {
    return ConfigReader(document_, YAML::Node(YAML::NodeType::Map), full_key(key) + ".");
  }
  if (!node.IsMap()) {
    fail(key, "expected a mapping of keys, got " + scalar_text(node));
  }
  return ConfigReader(document_, node, full_key(key) + ".");
}

std::vector<ConfigReader> ConfigReader::list(std::string_view key) const {
  const YAML::Node node = lookup(key);
  document_->used_as_nested.insert(full_key(key));
  std::vector<ConfigReader> items;
  if (!node.IsDefined() || node.IsNull()) {
    return items;
  }
  if (!node.IsSequence()) {
    fail(key, "expected a list of mappings, got " + scalar_text(node));
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item_key = std::string(key) + "[" + std::to_string(i) + "]";
    if (!node[i].IsMap()) {
      fail(item_key, "expected a mapping of keys, got " + scalar_text(node[i]));
    }
    document_->used.insert(full_key(item_key));
    document_->used_as_nested.insert(full_key(item_key));
    items.push_back(ConfigReader(document_, node[i], full_key(item_key) + "."));
  }
  return items;
}

void ConfigReader::check_all_keys_used() const {
  // Walks the document in file order so the first unknown key is reported.
  // Nested maps are walked with a "key." prefix; sequences of maps with "key".
  struct PrefixedWalker {
    const Document& doc;
    void walk_map(const YAML::Node& map, const std::string& prefix) const {
      for (const auto& entry : map) {
        const std::string key = prefix + entry.first.as<std::string>("?");
        if (doc.used.count(key) == 0) {
          const YAML::Mark mark = entry.first.Mark();
          throw ConfigError(doc.source + (mark.is_null() ? "" : ":" + std::to_string(mark.line + 1)) +
                            ": unknown key " + scalar_text(YAML::Node(key)));
        }
        if (doc.used_as_nested.count(key) == 0) {
          continue;
        }
        const YAML::Node& child = entry.second;
        if (child.IsMap()) {
          walk_map(child, key + ".");
        } else if (child.IsSequence()) {
          for (std::size_t i = 0; i < child.size(); ++i) {
            const std::string item = key + "[" + std::to_string(i) + "]";
            if (child[i].IsMap() && doc.used_as_nested.count(item) != 0) {
              walk_map(child[i], item + ".");
            }
          }
        }
      }
    }
  };
  if (node_.IsMap()) {
    PrefixedWalker{*document_}.walk_map(node_, prefix_);
  }
}

}  // namespace slamer

#include "localizer/class_map_check.hpp"

#include <algorithm>

#include "common/config/config_reader.hpp"

namespace slamer {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) {
    text += (text.empty() ? "" : ", ") + name;
  }
  return text.empty() ? "none" : text;
}

}  // namespace

std::string class_map_problem(const LocalizerOptions& options, const SemanticMap& map) {
  if (options.mode == LocalizerMode::kLfm) {
    return "";
  }
  const std::vector<std::string>& recognized = options.slamer.recognition_classes;
  std::vector<std::string> map_classes;
  for (const SemanticClass& c : map.classes) {
    map_classes.push_back(c.name);
  }
  for (const auto& [name, map_class] : options.slamer.class_map) {
    const std::string key = "key 'localizer.slamer.class_map." + name + "': ";
    if (std::find(recognized.begin(), recognized.end(), name) == recognized.end()) {
      return key + "'" + name + "' is not a class the recognizer emits (recognition_classes: " + join(recognized) + ")";
    }
    if (!map_class.empty() && map.class_index(map_class) < 0) {
      return key + "'" + map_class + "' is not a class of the map (it has: " + join(map_classes) +
             "); name one of them, or '' for free space";
    }
  }
  return "";
}

void check_class_map(const LocalizerOptions& options, const SemanticMap& map) {
  if (const std::string problem = class_map_problem(options, map); !problem.empty()) {
    throw ConfigError(problem);
  }
}

}  // namespace slamer

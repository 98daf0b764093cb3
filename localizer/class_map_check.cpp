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

std::string recognition_class_problem(const SlamerOptions& options, const std::string& name) {
  const std::vector<std::string>& known = options.recognition_classes;
  if (std::find(known.begin(), known.end(), name) != known.end()) {
    return "";
  }
  return "'" + name + "' is not a class the recognizer emits (recognition_classes: " + join(known) + ")";
}

std::string class_map_problem(const LocalizerOptions& options, const SemanticMap& map) {
  if (options.mode == LocalizerMode::kLfm) {
    return "";
  }
  std::vector<std::string> map_classes;
  for (const SemanticClass& c : map.classes) {
    map_classes.push_back(c.name);
  }
  for (const auto& [name, map_class] : options.slamer.class_map) {
    const std::string key = "key 'localizer.slamer.class_map." + name + "': ";
    if (const std::string problem = recognition_class_problem(options.slamer, name); !problem.empty()) {
      return key + problem;
    }
    if (!map_class.empty() && map.class_index(map_class) < 0) {
      return key + "'" + map_class + "' is not a class of the map (it has: " + join(map_classes) +
             "); name one of them, or '' for free space";
    }
  }
  for (const auto& [name, margin] : options.slamer.free_space_class_margins) {
    if (map.class_index(name) < 0) {
      return "key 'localizer.slamer.free_space_class_margins." + name + "': '" + name +
             "' is not a class of the map (it has: " + join(map_classes) + ")";
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

// The localizer's class_map against the map it runs on (issue 11): every
// entry must map a recognition class the recognizer emits
// (SlamerOptions::recognition_classes) to a class the map declares, or to ''
// (free space). A map class the map lacks would silently get no map prior
// (paper Eq. (7)), so it is an error at start-up, one line naming the key.
// LFM uses no classes and is not checked. The options loader stays pure: this
// runs where both the options and the map are known (LocalizerNode).
#pragma once

#include <string>

#include "common/map/semantic_map.hpp"
#include "localizer/localizer_options.hpp"

namespace slamer {

// "'NAME' is not a class the recognizer emits (recognition_classes: ...)", or
// "" when `name` is one (also the options loader's check, with file and line).
std::string recognition_class_problem(const SlamerOptions& options, const std::string& name);

// The first problem, "key 'localizer.slamer.class_map.NAME': ...", or "".
std::string class_map_problem(const LocalizerOptions& options, const SemanticMap& map);

// Throws ConfigError with class_map_problem()'s line.
void check_class_map(const LocalizerOptions& options, const SemanticMap& map);

}  // namespace slamer

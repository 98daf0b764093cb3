// What the localizer options' loader says of a YAML text: its one-line error,
// or "" when it accepts it. For the tests of keys and bad values.
#pragma once

#include <string>

#include "common/config/config_reader.hpp"
#include "localizer/localizer_options.hpp"

namespace slamer {

inline std::string localizer_options_error(const std::string& yaml) {
  try {
    parse_options<LocalizerOptions>(yaml, "localizer.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace slamer

// The shipped i-Cart mini parameter file (YP-Spur's format) the wheel tests read.
#pragma once

#include <string>

namespace slamer::tfrog {

inline std::string icart_mini_param_file() {
  return std::string(SLAMER_SOURCE_DIR "/config/robots/icart-mini.param");
}

}  // namespace slamer::tfrog

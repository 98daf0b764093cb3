// Reads what scoring needs from a log (slamer-eval, slamer-eval-suite): ground
// truth, the estimate, LINE_OBJECTS and SEMANTIC_OBJECTS. `estimate` names the
// estimate's channel; ODOMETRY is placed in the map by the first ground-truth
// pose. Damaged stretches and undecodable messages are skipped with a warning.
#pragma once

#include <string>

#include "tools/eval/eval_config.hpp"

namespace slamer {

RunInputs read_run(const std::string& path, const EvalChannels& channels, const std::string& estimate);

}  // namespace slamer

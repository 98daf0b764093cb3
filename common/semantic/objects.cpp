#include "common/semantic/objects.hpp"

#include <algorithm>

namespace slamer {

int most_likely(const std::vector<float>& probs) {
  if (probs.empty()) {
    return -1;
  }
  return static_cast<int>(std::max_element(probs.begin(), probs.end()) - probs.begin());
}

}  // namespace slamer

#include "common/semantic/objects.hpp"

#include <algorithm>

namespace slamer {

int most_likely(const std::vector<float>& probs) {
  if (probs.empty()) {
    return -1;
  }
  return static_cast<int>(std::max_element(probs.begin(), probs.end()) - probs.begin());
}

std::vector<std::string> paper_recognition_classes() {
  return {"open_door", "closed_door",   "open_glass_door", "closed_glass_door",
          "fence",     "no_entry_line", "free_space",      "others"};
}

}  // namespace slamer

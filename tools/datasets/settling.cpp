#include "tools/datasets/settling.hpp"

#include <cmath>

namespace slamer {

Settling settling(const std::vector<PoseReport>& poses, double max_jump, double ok_fraction) {
  Settling s;
  s.scans = static_cast<int64_t>(poses.size());
  if (poses.empty()) {
    return s;
  }
  const std::size_t n = poses.size();
  std::size_t after_last_jump = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (std::hypot(poses[k].pose.x - poses[k - 1].pose.x, poses[k].pose.y - poses[k - 1].pose.y) > max_jump) {
      after_last_jump = k;
    }
  }
  // OK poses from k to the end, for every k.
  std::vector<int64_t> ok_from(n + 1, 0);
  for (std::size_t k = n; k-- > 0;) {
    ok_from[k] = ok_from[k + 1] + (poses[k].status == BenchStatus::kOk ? 1 : 0);
  }
  s.ok_fraction = static_cast<double>(ok_from[0]) / static_cast<double>(n);
  s.end = poses.back().pose;
  for (std::size_t k = after_last_jump; k < n; ++k) {
    if (poses[k].status == BenchStatus::kOk &&
        static_cast<double>(ok_from[k]) >= ok_fraction * static_cast<double>(n - k)) {
      s.scan = static_cast<int64_t>(k);
      s.seconds = static_cast<double>(poses[k].utime - poses.front().utime) * 1e-6;
      break;
    }
  }
  return s;
}

}  // namespace slamer

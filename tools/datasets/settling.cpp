#include "tools/datasets/settling.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

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

Agreement agreement(const std::vector<std::vector<PoseReport>>& runs, double within) {
  if (runs.size() < 2) {
    throw std::invalid_argument("agreement needs two runs or more");
  }
  // Per scan utime, every run's pose; kept only where all runs have one.
  std::map<int64_t, std::vector<Pose2>> by_scan;
  for (const PoseReport& p : runs.front()) {
    by_scan[p.utime] = {p.pose};
  }
  for (std::size_t r = 1; r < runs.size(); ++r) {
    for (const PoseReport& p : runs[r]) {
      const auto it = by_scan.find(p.utime);
      if (it != by_scan.end() && it->second.size() == r) {
        it->second.push_back(p.pose);
      }
    }
  }
  std::vector<int64_t> utimes;
  std::vector<double> spread;
  for (const auto& [utime, poses] : by_scan) {
    if (poses.size() != runs.size()) {
      continue;
    }
    double widest = 0.0;
    for (std::size_t a = 0; a < poses.size(); ++a) {
      for (std::size_t b = a + 1; b < poses.size(); ++b) {
        widest = std::max(widest, std::hypot(poses[a].x - poses[b].x, poses[a].y - poses[b].y));
      }
    }
    utimes.push_back(utime);
    spread.push_back(widest);
  }
  Agreement a;
  a.scans = static_cast<int64_t>(spread.size());
  if (spread.empty()) {
    return a;
  }
  a.spread_at_end = spread.back();
  std::size_t k = spread.size();
  while (k > 0 && spread[k - 1] <= within) {
    --k;
  }
  if (k < spread.size()) {
    a.scan = static_cast<int64_t>(k);
    a.seconds = static_cast<double>(utimes[k] - utimes.front()) * 1e-6;
    a.spread_after = *std::max_element(spread.begin() + static_cast<std::ptrdiff_t>(k), spread.end());
  }
  return a;
}

std::vector<AgreeingGroup> agreeing_groups(const std::vector<std::vector<PoseReport>>& runs, double within) {
  // Union-find over the pairwise agreements.
  std::vector<std::size_t> root(runs.size());
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t r) {
    while (root[r] != r) {
      r = root[r];
    }
    return r;
  };
  for (std::size_t a = 0; a < runs.size(); ++a) {
    for (std::size_t b = a + 1; b < runs.size(); ++b) {
      if (agreement({runs[a], runs[b]}, within).scan) {
        root[find(b)] = find(a);
      }
    }
  }
  std::vector<AgreeingGroup> groups;
  std::vector<std::optional<std::size_t>> group_of_root(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    auto& g = group_of_root[find(r)];
    if (!g) {
      g = groups.size();
      groups.emplace_back();
    }
    groups[*g].runs.push_back(r);
  }
  for (AgreeingGroup& g : groups) {
    if (g.runs.size() >= 2) {
      std::vector<std::vector<PoseReport>> together;
      for (const std::size_t r : g.runs) {
        together.push_back(runs[r]);
      }
      g.agreement = agreement(together, within);
    }
  }
  return groups;
}

}  // namespace slamer

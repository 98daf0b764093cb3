// Global pose proposals from a scan against the map (issue 9, "recovery"; the
// dual proposal of Mixture-MCL, Thrun et al. 2001, made cheap): random poses
// over the map's free space (cells at distance 0 in the free-space field, at
// least `clearance` from an obstacle: where the robot's centre can be) are scored with a thinned
// copy of the scan in the likelihood field, and the best ones are returned to
// be injected as particles, which the full measurement model then weighs.
// Also draws poses uniformly over the free space (global localization).
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "common/map/likelihood_field.hpp"
#include "localizer/scan_fit.hpp"

namespace slamer {

class GlobalProposals {
 public:
  // Keeps the two fields (shared, immutable).
  GlobalProposals(std::shared_ptr<const DistanceField> free_space, std::shared_ptr<const DistanceField> obstacles,
                  double clearance);

  bool empty() const { return free_cells_ == 0; }
  std::size_t free_cells() const { return free_cells_; }
  // A pose uniform over the free space (rejection sampling in the free
  // cells' bounding box), heading uniform. Requires !empty().
  Pose2 uniform(std::mt19937& rng) const;
  // The `keep` best of `candidates` uniform poses for the scan `points`
  // (sensor frame, cells; thinned to about `beams`), best first.
  std::vector<Pose2> propose(const LikelihoodField& field, const ScanPoints& points, const Pose2& mount, int candidates,
                             int keep, int beams, std::mt19937& rng) const;

 private:
  bool usable(int x, int y) const;

  GridGeometry geometry_;
  std::shared_ptr<const DistanceField> free_space_;
  std::shared_ptr<const DistanceField> obstacles_;
  double clearance_;
  std::size_t free_cells_ = 0;
  int x0_ = 0, y0_ = 0, x1_ = -1, y1_ = -1;  // bounding box of the usable cells
};

}  // namespace slamer

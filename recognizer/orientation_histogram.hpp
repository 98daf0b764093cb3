// Length-weighted histogram of line orientations folded to [0, pi) (paper
// Sec. VI-B): a direction and its opposite are one orientation, and bins are
// circular, so 179 deg agrees with 1 deg (the published comparison never wrapped).
#pragma once

#include <vector>

namespace slamer {

class OrientationHistogram {
 public:
  explicit OrientationHistogram(int bins);

  void add(double angle, double weight);
  // Smoothed weight of the orientation's bin (half of each neighbour added)
  // is at least `min_fraction` of the largest smoothed bin.
  bool agrees(double angle, double min_fraction) const;
  double total() const { return total_; }

 private:
  int bin_of(double angle) const;
  double smoothed(int bin) const;

  std::vector<double> weights_;
  double total_ = 0.0;
};

}  // namespace slamer

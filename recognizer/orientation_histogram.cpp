#include "recognizer/orientation_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slamer {

OrientationHistogram::OrientationHistogram(int bins) : weights_(static_cast<std::size_t>(std::max(bins, 1)), 0.0) {}

int OrientationHistogram::bin_of(double angle) const {
  double folded = std::fmod(angle, std::numbers::pi);
  if (folded < 0.0) {
    folded += std::numbers::pi;
  }
  const int n = static_cast<int>(weights_.size());
  return std::min(n - 1, static_cast<int>(folded / std::numbers::pi * n));
}

double OrientationHistogram::smoothed(int bin) const {
  const int n = static_cast<int>(weights_.size());
  const auto at = [&](int b) { return weights_[static_cast<std::size_t>((b % n + n) % n)]; };
  return at(bin) + 0.5 * (at(bin - 1) + at(bin + 1));
}

void OrientationHistogram::add(double angle, double weight) {
  if (!std::isfinite(angle) || !(weight > 0.0)) {
    return;
  }
  weights_[static_cast<std::size_t>(bin_of(angle))] += weight;
  total_ += weight;
}

bool OrientationHistogram::agrees(double angle, double min_fraction) const {
  if (total_ <= 0.0 || !std::isfinite(angle)) {
    return false;
  }
  double peak = 0.0;
  for (int b = 0; b < static_cast<int>(weights_.size()); ++b) {
    peak = std::max(peak, smoothed(b));
  }
  return smoothed(bin_of(angle)) >= min_fraction * peak;
}

}  // namespace slamer

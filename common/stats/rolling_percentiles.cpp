#include "common/stats/rolling_percentiles.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

RollingPercentiles::RollingPercentiles(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {
  samples_.reserve(capacity_);
}

void RollingPercentiles::add(double value) {
  if (!std::isfinite(value)) {
    return;
  }
  if (samples_.size() < capacity_) {
    samples_.push_back(value);
  } else {
    samples_[next_] = value;
  }
  next_ = (next_ + 1) % capacity_;
}

double RollingPercentiles::percentile(double q) const {
  if (samples_.empty()) {
    return 0.0;
  }
  q = std::clamp(std::isfinite(q) ? q : 0.0, 0.0, 1.0);
  // Nearest rank: the smallest sample with at least q of the samples <= it.
  const auto n = samples_.size();
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  const std::size_t index = rank == 0 ? 0 : rank - 1;
  std::vector<double> copy = samples_;
  std::nth_element(copy.begin(), copy.begin() + static_cast<std::ptrdiff_t>(index), copy.end());
  return copy[index];
}

}  // namespace slamer

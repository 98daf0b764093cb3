// Percentiles over the most recent N samples (a ring buffer), e.g. the
// per-message processing time a process reports as p50/p99 in PROCESS_STATUS.
#pragma once

#include <cstddef>
#include <vector>

namespace slamer {

class RollingPercentiles {
 public:
  explicit RollingPercentiles(std::size_t capacity = 1000);

  void add(double value);  // non-finite values are ignored
  std::size_t size() const { return samples_.size(); }
  // Nearest-rank percentile, q in [0, 1], of the samples in the window; 0 if empty.
  double percentile(double q) const;

 private:
  std::size_t capacity_;
  std::size_t next_ = 0;
  std::vector<double> samples_;
};

}  // namespace slamer

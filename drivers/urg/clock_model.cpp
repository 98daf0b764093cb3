#include "drivers/urg/clock_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slamer::urg {

int64_t StampUnwrapper::unwrap(uint32_t raw_ms) {
  constexpr int64_t kRange = int64_t{1} << 24;
  raw_ms &= static_cast<uint32_t>(kRange - 1);
  if (!started_) {
    started_ = true;
    last_ = raw_ms;
    unwrapped_ = raw_ms;
    return unwrapped_;
  }
  int64_t delta = static_cast<int64_t>(raw_ms) - static_cast<int64_t>(last_);
  if (delta >= kRange / 2) {
    delta -= kRange;
  } else if (delta < -kRange / 2) {
    delta += kRange;
  }
  last_ = raw_ms;
  unwrapped_ += delta;
  return unwrapped_;
}

bool ClockModel::sync(const std::vector<SyncSample>& samples) {
  const std::size_t before = sync_samples_.size();
  for (const SyncSample& sample : samples) {
    if (sample.receive_us >= sample.send_us) {
      sync_samples_.push_back(sample);
    }
  }
  if (sync_samples_.size() == before) {
    return false;
  }
  fit_sync();
  ++sync_count_;
  lags_.clear();
  lag_reference_set_ = false;
  return true;
}

void ClockModel::add_sync_sample(const SyncSample& sample) {
  if (sample.receive_us < sample.send_us) {
    return;
  }
  sync_samples_.push_back(sample);
  while (static_cast<int>(sync_samples_.size()) > options_.max_sync_samples) {
    sync_samples_.pop_front();
  }
  fit_sync();
}

// Each sample: host(d) <= receive and host(d + 1 ms) > send, with host(x) =
// ref_host + a + g * (x - ref_device). For a gain g the offsets allowed are
// [lo(g), hi(g)], hi - lo concave in g. With samples over a long enough span
// the gain is the middle of the feasible gains (or the least violated one);
// otherwise the gain stays and only the offset is fitted.
void ClockModel::fit_sync() {
  const SyncSample& newest = sync_samples_.back();
  const double ref_device_us = static_cast<double>(newest.device_ms) * 1000.0;
  const int64_t ref_host_us = newest.receive_us;
  // Until the gain is known the offset uses only the last second of samples:
  // an unknown drift of 100 ppm then bends them by 0.1 ms at most.
  int64_t oldest_us = std::numeric_limits<int64_t>::min();  // the gain search uses every sample
  auto bounds = [&](double g, double* lo, double* hi) {
    *lo = -std::numeric_limits<double>::infinity();
    *hi = std::numeric_limits<double>::infinity();
    for (const SyncSample& s : sync_samples_) {
      if (s.receive_us < oldest_us && &s != &newest) {
        continue;
      }
      const double d_us = static_cast<double>(s.device_ms) * 1000.0 - ref_device_us;
      *hi = std::min(*hi, static_cast<double>(s.receive_us - ref_host_us) - g * d_us);
      *lo = std::max(*lo, static_cast<double>(s.send_us - ref_host_us) - g * (d_us + 1000.0));
    }
    return *hi - *lo;
  };
  const double span_s = static_cast<double>(sync_samples_.back().receive_us - sync_samples_.front().send_us) * 1e-6;
  double g = gain_;
  // The gain search costs ~100 passes: every 20th sample (1 s at 20 Hz) is plenty.
  if (span_s >= options_.min_gain_span_s && sync_samples_.size() >= 20 && ++since_gain_fit_ >= 20) {
    since_gain_fit_ = 0;
    const double g0 = 1.0 - options_.max_gain_error, g1 = 1.0 + options_.max_gain_error;
    double a = g0, b = g1, lo = 0, hi = 0;
    for (int i = 0; i < 50; ++i) {
      const double m1 = a + (b - a) / 3.0, m2 = b - (b - a) / 3.0;
      if (bounds(m1, &lo, &hi) < bounds(m2, &lo, &hi)) {
        a = m1;
      } else {
        b = m2;
      }
    }
    g = 0.5 * (a + b);
    if (bounds(g, &lo, &hi) >= 0) {
      auto edge = [&](double feasible, double infeasible) {
        for (int i = 0; i < 40; ++i) {
          const double m = 0.5 * (feasible + infeasible);
          double l, h;
          (bounds(m, &l, &h) >= 0 ? feasible : infeasible) = m;
        }
        return feasible;
      };
      g = 0.5 * (edge(g, g0) + edge(g, g1));
    }
    gain_ = g;
    gain_from_sync_ = true;
  }
  if (!gain_from_sync_) {
    oldest_us = newest.receive_us - options_.offset_window_us;
  }
  double lo, hi;
  const double width = bounds(g, &lo, &hi);
  sync_width_us_ = width;
  anchor_device_us_ = ref_device_us;
  anchor_host_us_ = ref_host_us + static_cast<int64_t>(std::llround(0.5 * (lo + hi)));
  anchored_ = true;
  synced_ = true;
}

void ClockModel::reset_stream() {
  sync_samples_.clear();
  gain_from_sync_ = false;
  stamps_.clear();
  lags_.clear();
  lag_reference_set_ = false;
  synced_ = false;
  anchored_ = false;
}

int64_t ClockModel::host_of_device(double device_us) const {
  return anchor_host_us_ + static_cast<int64_t>(std::llround(gain_ * (device_us - anchor_device_us_)));
}

double ClockModel::first_beam_device_us(int64_t device_ms, int64_t scan_period_us) {
  const double raw = static_cast<double>(device_ms) + 0.5;  // the stamp is the floor of the true time
  const double nominal = static_cast<double>(scan_period_us) / 1000.0;
  if (!stamps_.empty()) {
    const Stamp& last = stamps_.back();
    const double period = period_ms_ > 0 ? period_ms_ : nominal;
    const int64_t step = period > 0 ? std::llround(static_cast<double>(device_ms - last.device_ms) / period) : 1;
    if (step <= 0 || step > 1000) {
      stamps_.clear();  // out of order or a long gap: start the fit again
    } else {
      next_index_ = last.index + step;
    }
  }
  if (stamps_.empty()) {
    next_index_ = 0;
    period_ms_ = 0;
    since_phase_fit_ = 0;
  }
  stamps_.push_back({next_index_, device_ms});
  while (static_cast<int>(stamps_.size()) > options_.phase_window) {
    stamps_.pop_front();
  }
  if (stamps_.size() < 8 || nominal <= 0) {
    return raw * 1000.0;
  }
  if (period_ms_ <= 0 || ++since_phase_fit_ >= options_.drift_every) {
    since_phase_fit_ = 0;
    fit_phase(nominal);
  }
  if (period_ms_ <= 0) {
    return raw * 1000.0;
  }
  const double fitted = phase_ms_ + period_ms_ * static_cast<double>(next_index_ - phase_index_);
  const double low = static_cast<double>(device_ms);
  if (fitted < low - 0.5 || fitted > low + 1.5) {
    // The stamps no longer follow one period (a scan-rate change, a jittering motor): start again.
    stamps_.clear();
    stamps_.push_back({0, device_ms});
    next_index_ = 0;
    period_ms_ = 0;
    return raw * 1000.0;
  }
  // The stamp is the floor of the true time: stay inside [stamp, stamp + 1 ms).
  return std::clamp(fitted, low, low + 0.999) * 1000.0;
}

// Every stamp says stamp <= phase + period * index < stamp + 1. For a period P
// the phases allowed form [lo(P), hi(P)); lo is convex and hi concave in P, so
// w = hi - lo is concave. The periods with w >= 0 form [Pmin, Pmax]; the time
// of the newest scan K then lies in [lo(Pmin) + Pmin K, hi(Pmax) + Pmax K] and
// its middle is taken. With the phase walking through the millisecond grid
// this pins the first beam far below 1 ms. No feasible period (a jittering
// motor): the least violated one (minimax fit).
void ClockModel::fit_phase(double nominal_ms) {
  const Stamp& first = stamps_.front();
  auto bounds = [&](double period, double* lo, double* hi) {
    *lo = -std::numeric_limits<double>::infinity();
    *hi = std::numeric_limits<double>::infinity();
    for (const Stamp& st : stamps_) {
      const double k = static_cast<double>(st.index - first.index);
      const double d = static_cast<double>(st.device_ms - first.device_ms);
      *lo = std::max(*lo, d - period * k);
      *hi = std::min(*hi, d + 1.0 - period * k);
    }
    return *hi - *lo;
  };
  const double a0 = nominal_ms * (1.0 - 2.0 * options_.max_gain_error);
  const double b0 = nominal_ms * (1.0 + 2.0 * options_.max_gain_error);
  double a = a0, b = b0, lo = 0, hi = 0;
  for (int i = 0; i < 60; ++i) {
    const double m1 = a + (b - a) / 3.0;
    const double m2 = b - (b - a) / 3.0;
    if (bounds(m1, &lo, &hi) < bounds(m2, &lo, &hi)) {
      a = m1;
    } else {
      b = m2;
    }
  }
  const double best = 0.5 * (a + b);
  const double best_width = bounds(best, &lo, &hi);
  const double last_k = static_cast<double>(stamps_.back().index - first.index);
  if (best_width < -0.5) {
    period_ms_ = 0;  // far from periodic: use the raw stamps
    return;
  }
  if (best_width < 0) {
    period_ms_ = best;
    phase_index_ = first.index;
    phase_ms_ = static_cast<double>(first.device_ms) + 0.5 * (lo + hi);
    return;
  }
  auto edge = [&](double feasible, double infeasible) {
    for (int i = 0; i < 50; ++i) {
      const double m = 0.5 * (feasible + infeasible);
      double l, h;
      (bounds(m, &l, &h) >= 0 ? feasible : infeasible) = m;
    }
    return feasible;
  };
  const double pmin = edge(best, a0);
  const double pmax = edge(best, b0);
  double lo_min, hi_min, lo_max, hi_max;
  bounds(pmin, &lo_min, &hi_min);
  bounds(pmax, &lo_max, &hi_max);
  const double earliest = lo_min + pmin * last_k;
  const double latest = hi_max + pmax * last_k;
  period_ms_ = 0.5 * (pmin + pmax);
  phase_index_ = stamps_.back().index;
  phase_ms_ = static_cast<double>(first.device_ms) + 0.5 * (earliest + latest);
}

void ClockModel::re_anchor(double device_us) {
  anchor_host_us_ = host_of_device(device_us);
  anchor_device_us_ = device_us;
}

void ClockModel::track_drift(double device_us, int64_t arrival_us) {
  // lag = (arrival - device), relative to the first scan's so doubles keep their precision.
  const double raw_lag = static_cast<double>(arrival_us) - device_us;
  if (!lag_reference_set_) {
    lag_reference_us_ = raw_lag;
    lag_reference_set_ = true;
  }
  if (!lags_.empty() && device_us <= lags_.back().device_us) {
    return;  // out of order
  }
  lags_.push_back({device_us, raw_lag - lag_reference_us_});
  if (static_cast<int>(lags_.size()) > options_.max_drift_points) {
    // Sliding window from here on: move the anchor so older gains stay where they applied.
    lags_.pop_front();
    re_anchor(device_us);
  }
  if (++since_drift_update_ < options_.drift_every || static_cast<int>(lags_.size()) < options_.min_drift_points) {
    return;
  }
  since_drift_update_ = 0;
  // The envelope: the minimum lag in each of a few equal spans of device time
  // (each holds about as many scans, so their bias is the same), then a least-squares line.
  const int spans = std::clamp(static_cast<int>(lags_.size()) / 200, 4, 8);
  const double x0 = lags_.front().device_us;
  const double width = (lags_.back().device_us - x0) / spans;
  if (width <= 0) {
    return;
  }
  std::vector<LagPoint> minima(static_cast<std::size_t>(spans), {0, std::numeric_limits<double>::infinity()});
  for (const LagPoint& p : lags_) {
    const int i = std::min(spans - 1, static_cast<int>((p.device_us - x0) / width));
    if (p.lag_us < minima[static_cast<std::size_t>(i)].lag_us) {
      minima[static_cast<std::size_t>(i)] = {p.device_us - x0, p.lag_us};
    }
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const LagPoint& m : minima) {
    if (std::isfinite(m.lag_us)) {
      sx += m.device_us;
      sy += m.lag_us;
      sxx += m.device_us * m.device_us;
      sxy += m.device_us * m.lag_us;
      n += 1;
    }
  }
  const double denominator = n * sxx - sx * sx;
  if (n >= 3 && denominator > 0) {
    // The anchor stays at the sync: the gain's error shrinks as the envelope grows longer.
    const double slope = (n * sxy - sx * sy) / denominator;
    if (std::abs(slope) <= options_.max_gain_error && !gain_from_sync_) {
      gain_ = 1.0 + slope;
    }
  }
}

int64_t ClockModel::scan_utime(int64_t device_ms, int64_t scan_period_us, int64_t arrival_us) {
  const double device_us = first_beam_device_us(device_ms, scan_period_us);
  if (!anchored_) {
    anchor_device_us_ = device_us;
    anchor_host_us_ = arrival_us;
    anchored_ = true;
  }
  track_drift(device_us, arrival_us);
  return host_of_device(device_us);
}

}  // namespace slamer::urg

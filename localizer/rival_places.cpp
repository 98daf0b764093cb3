#include "localizer/rival_places.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>

namespace slamer {

namespace {

bool close_to(const Pose2& a, const Pose2& b, const PlaceOptions& options) {
  return std::hypot(a.x - b.x, a.y - b.y) <= options.radius && std::abs(angle_diff(a.theta, b.theta)) <= options.turn;
}

}  // namespace

void systematic_draw(const std::vector<Particle>& set, const std::vector<std::size_t>& indices, double reference,
                     std::optional<double> total, std::size_t count, double log_weight, std::mt19937& rng,
                     std::vector<Particle>* out) {
  if (count == 0 || indices.empty()) {
    return;
  }
  std::vector<double> weights;
  weights.reserve(indices.size());
  for (const std::size_t i : indices) {
    weights.push_back(std::exp(set[i].log_weight - reference));
  }
  const double step = total.value_or(std::accumulate(weights.begin(), weights.end(), 0.0)) / static_cast<double>(count);
  std::uniform_real_distribution<double> offset(0.0, step);
  double pointer = offset(rng);
  double cumulative = weights[0];
  std::size_t source = 0;
  for (std::size_t k = 0; k < count; ++k) {
    while (pointer > cumulative && source + 1 < indices.size()) {
      ++source;
      cumulative += weights[source];
    }
    out->push_back({set[indices[source]].pose, log_weight});
    pointer += step;
  }
}

std::vector<Place> places_of(const std::vector<Particle>& set, const PlaceOptions& options) {
  std::vector<std::size_t> order(set.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return set[a].log_weight > set[b].log_weight; });
  // Every particle finds its place among the seeds of its own and the eight
  // neighbouring cells of `radius`: a uniform cloud has thousands of places.
  const auto cell_of = [&](const Pose2& p) {
    return std::pair{static_cast<int64_t>(std::floor(p.x / options.radius)),
                     static_cast<int64_t>(std::floor(p.y / options.radius))};
  };
  std::map<std::pair<int64_t, int64_t>, std::vector<std::size_t>> seeds_in;
  std::vector<Place> places;
  std::vector<double> sums;  // linear, relative to the most likely particle's weight
  const double peak = set.empty() ? 0.0 : set[order[0]].log_weight;
  for (const std::size_t i : order) {
    const auto [cx, cy] = cell_of(set[i].pose);
    std::size_t found = places.size();
    for (int64_t dx = -1; dx <= 1 && found == places.size(); ++dx) {
      for (int64_t dy = -1; dy <= 1 && found == places.size(); ++dy) {
        const auto it = seeds_in.find({cx + dx, cy + dy});
        if (it == seeds_in.end()) {
          continue;
        }
        for (const std::size_t p : it->second) {
          if (close_to(set[i].pose, places[p].seed, options) && p < found) {
            found = p;
          }
        }
      }
    }
    if (found == places.size()) {
      places.push_back({set[i].pose, 0.0, {}});
      sums.push_back(0.0);
      seeds_in[{cx, cy}].push_back(found);
    }
    places[found].members.push_back(i);
    sums[found] += std::exp(set[i].log_weight - peak);
  }
  for (std::size_t p = 0; p < places.size(); ++p) {
    places[p].log_weight = peak + std::log(sums[p]);
  }
  std::stable_sort(places.begin(), places.end(),
                   [](const Place& a, const Place& b) { return a.log_weight > b.log_weight; });
  if (places.size() > options.max_places) {
    places.resize(options.max_places);
  }
  return places;
}

std::vector<const Place*> rivals_in(const std::vector<Place>& places, const PlaceOptions& options) {
  std::vector<const Place*> rivals;
  if (places.empty()) {
    return rivals;
  }
  for (const Place& p : places) {
    if (p.log_weight >= places.front().log_weight - options.margin) {
      rivals.push_back(&p);
    }
  }
  return rivals;
}

void rescore_places(std::vector<Particle>* set, const std::vector<Place>& places, const std::vector<double>& totals) {
  for (std::size_t k = 0; k < places.size() && k < totals.size(); ++k) {
    const std::vector<std::size_t>& members = places[k].members;
    if (members.empty()) {
      continue;
    }
    double peak = -std::numeric_limits<double>::infinity();
    for (const std::size_t i : members) {
      peak = std::max(peak, (*set)[i].log_weight);
    }
    if (!std::isfinite(peak)) {
      continue;  // every particle of it at zero weight: no relative weights to keep
    }
    double sum = 0.0;
    for (const std::size_t i : members) {
      sum += std::exp((*set)[i].log_weight - peak);
    }
    const double shift = totals[k] - (peak + std::log(sum));
    for (const std::size_t i : members) {
      (*set)[i].log_weight += shift;
    }
  }
}

std::vector<Particle> resample_keeping_places(const std::vector<Particle>& set, const std::vector<Place>& places,
                                              const PlaceOptions& options, std::size_t n, std::mt19937& rng) {
  std::vector<Particle> next;
  if (set.empty() || n == 0) {
    return next;
  }
  if (places.empty()) {  // one place of them all: ordinary systematic resampling
    Place all{set.front().pose, 0.0, std::vector<std::size_t>(set.size())};
    std::iota(all.members.begin(), all.members.end(), std::size_t{0});
    return resample_keeping_places(set, {all}, options, n, rng);
  }
  const std::vector<const Place*> kept = rivals_in(places, options);
  std::vector<bool> in_kept(set.size(), false);
  for (const Place* p : kept) {
    for (const std::size_t i : p->members) {
      in_kept[i] = true;
    }
  }
  std::vector<std::size_t> rest;
  double peak = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < set.size(); ++i) {
    peak = std::max(peak, set[i].log_weight);
    if (!in_kept[i]) {
      rest.push_back(i);
    }
  }
  double rest_sum = 0.0;
  for (const std::size_t i : rest) {
    rest_sum += std::exp(set[i].log_weight - peak);
  }
  const double rest_log_weight = rest_sum > 0.0 ? peak + std::log(rest_sum) : -std::numeric_limits<double>::infinity();
  // Counts: the rest its share of n by weight; the kept places the others
  // in equal parts (the best place the remainder).
  const std::size_t rest_count =
      rest.empty() ? 0
                   : std::min(n > kept.size() ? n - kept.size() : 0,
                              static_cast<std::size_t>(
                                  std::lround(static_cast<double>(n) * std::exp(std::min(rest_log_weight, 0.0)))));
  std::vector<std::size_t> counts(kept.size(), (n - rest_count) / kept.size());
  counts.front() += (n - rest_count) % kept.size();
  counts.push_back(rest_count);
  next.reserve(n);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    systematic_draw(set, kept[k]->members, peak, std::nullopt, counts[k],
                    kept[k]->log_weight - std::log(static_cast<double>(counts[k])), rng, &next);
  }
  if (counts.back() > 0) {
    systematic_draw(set, rest, peak, std::nullopt, counts.back(),
                    rest_log_weight - std::log(static_cast<double>(counts.back())), rng, &next);
  }
  return next;
}

}  // namespace slamer

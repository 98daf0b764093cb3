// ParticleFilter's object term, SLAMER's weight from the recognized line
// objects (paper Eqs. (7)-(9)): each object's samples placed on the map's
// class distance fields at the particle's pose, the map prior of Eq. (7) per
// recognition class, the Dirichlet recognition likelihood of Eq. (8) with the
// training prior divided out, summed over classes as Eq. (9). The per-class
// terms at the best particle are what update() makes the class posteriors of.
// Split from particle_filter.cpp for size.
#include <algorithm>
#include <cmath>

#include "localizer/particle_filter_internal.hpp"
#include "localizer/recognition_model.hpp"

namespace slamer {

namespace {

constexpr int kFreeSpace = -1;
constexpr int kNoField = -2;

// The mean distance of `n` samples, those off the map (not in `cells`) at `far`;
// fields saturate at or beyond `far` (also with no cell of the class at all).
double mean_distance(const DistanceField& distances, const std::vector<Cell>& cells, std::size_t n, double far) {
  double sum = far * static_cast<double>(n - cells.size());
  for (const Cell& cell : cells) {
    sum += std::min(static_cast<double>(distances.at(cell.x, cell.y)), far);
  }
  return sum / static_cast<double>(n);
}

// The largest distance of `n` samples, those off the map at `far`.
double farthest_distance(const DistanceField& distances, const std::vector<Cell>& cells, std::size_t n, double far) {
  double farthest = cells.size() < n ? far : 0.0;
  for (const Cell& cell : cells) {
    farthest = std::max(farthest, std::min(static_cast<double>(distances.at(cell.x, cell.y)), far));
  }
  return farthest;
}

}  // namespace

ParticleFilter::PreparedObjects ParticleFilter::prepare_objects(const LineObjectSet& set) const {
  PreparedObjects prepared;
  prepared.class_names = set.class_names;
  // pi^exponent per class of the message; a class the config does not know keeps its probability (pi 1).
  std::vector<double> training_prior;
  if (!options_.slamer.training_prior.empty()) {
    for (const std::string& name : set.class_names) {
      const auto it = options_.slamer.training_prior.find(name);
      training_prior.push_back(it == options_.slamer.training_prior.end()
                                   ? 1.0
                                   : std::pow(it->second, options_.slamer.training_prior_exponent));
    }
  }
  prepared.training_prior = training_prior;
  for (const LineObject& object : set.objects) {
    const bool finite = object.start.allFinite() && object.end.allFinite() &&
                        std::all_of(object.probs.begin(), object.probs.end(), [](float p) { return std::isfinite(p); });
    if (object.probs.size() != set.class_names.size() || set.class_names.empty() || !finite) {
      continue;  // a malformed object tells nothing (and a NaN would poison every weight)
    }
    PreparedObjects::Object o;
    o.object = object;
    const int n = options_.slamer.object_samples;
    for (int s = 0; s < n; ++s) {
      const double t = n == 1 ? 0.5 : static_cast<double>(s) / (n - 1);
      o.samples.push_back(object.start + t * (object.end - object.start));
    }
    const std::vector<float> likelihoods =
        divide_out_prior(object.probs, training_prior, options_.slamer.min_probability);
    for (std::size_t l = 0; l < set.class_names.size(); ++l) {
      o.log_recognition.push_back(log_dirichlet(likelihoods, static_cast<int>(l), options_.slamer.dirichlet_a1,
                                                options_.slamer.dirichlet_a2, options_.slamer.min_probability));
      int field = kNoField;
      const auto mapped = options_.slamer.class_map.find(set.class_names[l]);
      if (mapped != options_.slamer.class_map.end()) {
        if (mapped->second.empty()) {
          field = kFreeSpace;
        } else {
          const auto it = std::find(map_classes_.begin(), map_classes_.end(), mapped->second);
          field = it == map_classes_.end() ? kNoField : static_cast<int>(it - map_classes_.begin());
        }
      }
      o.field.push_back(field);
    }
    prepared.objects.push_back(std::move(o));
  }
  return prepared;
}

double ParticleFilter::objects_log_likelihood(const Pose2& pose, const PreparedObjects& objects,
                                              const DistanceField& free_space, double unmapped_probability,
                                              SpatialLineEnds spatial_line_ends,
                                              PhysicalLineDistance physical_line_distance,
                                              std::vector<std::vector<double>>* class_terms, bool memo) const {
  // The sensor pose on the grid: one transform per particle.
  double c = 1.0, s = 0.0;
  const Pose2 grid = sensor_on_grid(pose, &c, &s);
  const double to_cells = 1.0 / geometry_.resolution;
  // An object off the map, or a class with no cells, is this far from it: the
  // same for every pose, so it neither helps nor hurts.
  const double far = 3.0 * options_.slamer.prior_sigma;
  // Most classes have no cell near an object: their prior is this one value.
  // d below is exactly `far` when every sample saturates (n times `far` over n,
  // exact for the shipped 3 samples); where rounding leaves it an ulp off, the
  // prior is computed instead, to the same value.
  const double prior_at_far = log_map_prior(far, options_.slamer.prior_sigma, unmapped_probability);
  double total = 0.0;
  std::vector<double> terms;
  std::vector<Cell> cells;        // sample cells on the map; off-map samples are left out
  std::vector<Cell> inner_cells;  // of the samples between the ends, if they may be used
  std::vector<int32_t> key;       // every sample's cell, off the map (-1, -1): the memo's key
  const bool use_memo = memo && class_terms == nullptr;
  for (const PreparedObjects::Object& o : objects.objects) {
    cells.clear();
    inner_cells.clear();
    key.clear();
    for (std::size_t k = 0; k < o.samples.size(); ++k) {
      const Eigen::Vector2d& p = o.samples[k];
      const double gx = (c * p.x() - s * p.y() + grid.x) * to_cells;
      const double gy = (s * p.x() + c * p.y() + grid.y) * to_cells;
      if (gx >= 0.0 && gy >= 0.0 && gx < geometry_.width && gy < geometry_.height) {
        cells.push_back({static_cast<int>(gx), static_cast<int>(gy)});
        key.insert(key.end(), {cells.back().x, cells.back().y});
        if (spatial_line_ends != SpatialLineEnds::kScored && k > 0 && k + 1 < o.samples.size()) {
          inner_cells.push_back(cells.back());
        }
      } else {
        key.insert(key.end(), {-1, -1});
      }
    }
    if (use_memo) {
      if (const auto known = o.weight_by_cells.find(key); known != o.weight_by_cells.end()) {
        total += known->second;
        continue;
      }
    }
    const std::size_t inner_samples = o.samples.size() >= 3 ? o.samples.size() - 2 : 0;
    terms.assign(o.field.size(), 0.0);
    for (std::size_t l = 0; l < o.field.size(); ++l) {
      const int field = o.field[l];
      double d = far;
      if (field != kNoField) {
        const DistanceField& distances =
            field == kFreeSpace ? free_space : *class_distances_[static_cast<std::size_t>(field)];
        const bool spatial = o.object.kind == LineKind::kSpatial;
        const bool inner = inner_samples > 0 && (spatial_line_ends == SpatialLineEnds::kLeftOutForFreeSpace
                                                     ? field == kFreeSpace
                                                     : spatial_line_ends == SpatialLineEnds::kLeftOut && spatial);
        d = !spatial && physical_line_distance == PhysicalLineDistance::kFarthest
                ? farthest_distance(distances, cells, o.samples.size(), far)
                : mean_distance(distances, inner ? inner_cells : cells, inner ? inner_samples : o.samples.size(), far);
      }
      terms[l] = o.log_recognition[l] +
                 (d == far ? prior_at_far : log_map_prior(d, options_.slamer.prior_sigma, unmapped_probability));
    }
    const double weight = options_.slamer.object_weight * log_sum_exp(terms);
    total += weight;
    if (use_memo) {
      o.weight_by_cells.emplace(key, weight);
    }
    if (class_terms != nullptr) {
      class_terms->push_back(terms);
    }
  }
  return total;
}

double ParticleFilter::objects_weight(const Pose2& pose, const PreparedObjects& objects) const {
  return options_.mode == LocalizerMode::kSlamer
             ? objects_log_likelihood(pose, objects, *free_distance_, options_.slamer.unmapped_probability,
                                      SpatialLineEnds::kScored, PhysicalLineDistance::kMean, nullptr, true)
             : 0.0;
}

std::vector<double> ParticleFilter::objects_weights(const std::vector<Pose2>& poses,
                                                    const LineObjectSet& objects) const {
  const PreparedObjects prepared = prepare_objects(objects);
  std::vector<double> weights;
  for (const Pose2& pose : poses) {
    weights.push_back(objects_weight(pose, prepared));
  }
  return weights;
}

double ParticleFilter::object_log_likelihood(const Pose2& pose, const LineObject& object,
                                             const std::vector<std::string>& classes) const {
  LineObjectSet set;
  set.class_names = classes;
  set.objects = {object};
  return objects_log_likelihood(pose, prepare_objects(set), *free_distance_, options_.slamer.unmapped_probability,
                                SpatialLineEnds::kScored, PhysicalLineDistance::kMean, nullptr);
}

}  // namespace slamer

#include "localizer/recognition_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace slamer {

double log_dirichlet(const std::vector<float>& probs, int true_class, double a1, double a2, double min_probability) {
  const auto n = static_cast<double>(probs.size());
  double log_density = std::lgamma(a1 + (n - 1.0) * a2) - std::lgamma(a1) - (n - 1.0) * std::lgamma(a2);
  for (std::size_t l = 0; l < probs.size(); ++l) {
    const double a = static_cast<int>(l) == true_class ? a1 : a2;
    const double p = std::max(static_cast<double>(probs[l]), min_probability);
    log_density += (a - 1.0) * std::log(p);
  }
  return log_density;
}

std::vector<float> divide_out_prior(const std::vector<float>& probs, const std::vector<double>& prior,
                                    double min_probability) {
  if (prior.empty()) {
    return probs;
  }
  std::vector<double> q(probs.size());
  double sum = 0.0;
  for (std::size_t l = 0; l < probs.size(); ++l) {
    q[l] = std::max(static_cast<double>(probs[l]), min_probability) / prior[l];
    sum += q[l];
  }
  std::vector<float> out(probs.size());
  for (std::size_t l = 0; l < probs.size(); ++l) {
    out[l] = static_cast<float>(q[l] / sum);
  }
  return out;
}

double log_normal_density(double d, double sigma) {
  return -0.5 * (d / sigma) * (d / sigma) - std::log(sigma * std::sqrt(2.0 * std::numbers::pi));
}

double log_map_prior(double d, double sigma, double unmapped_probability) {
  if (unmapped_probability <= 0.0) {
    return log_normal_density(d, sigma);
  }
  const double mapped = (1.0 - unmapped_probability) * std::exp(-0.5 * (d / sigma) * (d / sigma));
  return log_normal_density(0.0, sigma) + std::log(mapped + unmapped_probability);
}

std::vector<double> with_unmapped_objects(const std::vector<double>& terms, const std::vector<double>& log_recognition,
                                          const std::vector<double>& base_rates, double unmapped_probability) {
  const std::size_t n = terms.size();
  if (unmapped_probability <= 0.0 || n == 0 || log_recognition.size() != n) {
    return terms;
  }
  std::vector<double> log_prior(n);
  for (std::size_t l = 0; l < n; ++l) {
    log_prior[l] = terms[l] - log_recognition[l];
  }
  const double prior_norm = log_sum_exp(log_prior);
  double rate_sum = 0.0;
  for (std::size_t l = 0; l < n; ++l) {
    rate_sum += base_rates.size() == n ? base_rates[l] : 1.0;
  }
  std::vector<double> mixed(n);
  for (std::size_t l = 0; l < n; ++l) {
    const double mapped = std::isfinite(prior_norm) ? std::exp(log_prior[l] - prior_norm) : 0.0;
    const double rate = (base_rates.size() == n ? base_rates[l] : 1.0) / rate_sum;
    mixed[l] = log_recognition[l] + std::log((1.0 - unmapped_probability) * mapped + unmapped_probability * rate);
  }
  return mixed;
}

double log_sum_exp(const std::vector<double>& terms) {
  if (terms.empty()) {
    return -std::numeric_limits<double>::infinity();
  }
  const double peak = *std::max_element(terms.begin(), terms.end());
  if (!std::isfinite(peak)) {
    return peak;
  }
  double sum = 0.0;
  for (const double t : terms) {
    sum += std::exp(t - peak);
  }
  return peak + std::log(sum);
}

}  // namespace slamer

// SLAMER's per-object terms (paper Eqs. (7)-(9)), in log space.
//
// Recognition model: the recognizer's probability vector c-hat is Dirichlet
// distributed with concentration a1 on the true class and a2 elsewhere,
//   log Dir(c; a) = lgamma(sum a) - sum lgamma(a_l) + sum (a_l - 1) log c_l,
// with lgamma throughout (tgamma overflows above about 171).
// Map prior: p(c = l | x, m) = N(d_l; 0, sigma_d), d_l the representative
// distance from the object, placed by the particle's pose, to the nearest
// cell of class l's map. It depends on the pose and is not renormalized per
// particle (the published implementation did, and its SLAMER term cancelled).
//
// The recognizer's probabilities are class posteriors: its rules are class
// frequencies per feature bin (slamer-calibrate-recognizer), so they carry the
// class frequencies pi of the worlds they were fitted on. In SLAMER the map
// prior takes pi's place, so Eq. (8) is given c-hat with pi divided out,
// q_l = (c_l / pi_l) / sum_k (c_k / pi_k); otherwise a class that is rare in
// training (no-entry lines: 0.2 % of the objects) counts as improbable twice,
// and no map prior brings it back where the map has one.
#pragma once

#include <vector>

namespace slamer {

// log Dir(probs; a) with a_l = (l == true_class ? a1 : a2); probs floored at min_probability.
double log_dirichlet(const std::vector<float>& probs, int true_class, double a1, double a2, double min_probability);

// q above, with every c_l floored at min_probability first; `prior` holds
// pi_l per class of `probs` (> 0). An empty prior leaves probs as they are.
std::vector<float> divide_out_prior(const std::vector<float>& probs, const std::vector<double>& prior,
                                    double min_probability);

// log N(d; 0, sigma) (a density, with its normalizer).
double log_normal_density(double d, double sigma);

// Eq. (7)'s map prior with a floor: log of (1 - u) N(d; 0, sigma) + u N(0; 0, sigma),
// u the probability that the object is not in the map at all (then its
// distance to the map says nothing). u = 0 is log_normal_density.
double log_map_prior(double d, double sigma, double unmapped_probability);

// A class posterior's terms (log Dir + log map prior per class, as Eq. (4)
// scores them) with the map prior made a mixture: with probability
// `unmapped_probability` the object is not the map's (furniture added, a door
// moved), and then its class follows the base rates `base_rates` (pi^e, the
// training prior divide_out_prior took out; empty: uniform) instead of the
// map, p(l | x, m) = (1 - u) p_map(l) + u b_l / sum b, p_map the map prior
// normalized over the classes. Without it an object the map knows nothing of
// (all its classes' distances saturated) took the class the divided-out prior
// favours most: the rarest (closed doors on added furniture).
std::vector<double> with_unmapped_objects(const std::vector<double>& terms, const std::vector<double>& log_recognition,
                                          const std::vector<double>& base_rates, double unmapped_probability);

// log of sum_l exp(terms[l]), stable; -inf for an empty list.
double log_sum_exp(const std::vector<double>& terms);

}  // namespace slamer

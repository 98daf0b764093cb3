// Rival places in a particle cloud after a global localization, and a
// resampling that keeps them until the scans decide between them.
//
// A building of repeated bays (Wean Hall: doors and alcoves every few metres
// along its corridors) has places that fit a scan, and a run of scans, about
// as well as the right one. Ordinary resampling draws particles in proportion
// to their weights, so the place a few early scans favoured takes every
// particle, and the evidence of the scans after (which on Wean log 3 put the
// right place 450 nats ahead of a look-alike 6 m along the corridor, though
// 50 behind after 100 scans) has nothing left to weigh. This is the
// clustered particle filter's remedy (Milstein, Sanchez and Williamson,
// AAAI 2002, in its simplest form): the cloud is grouped into places,
// particles are resampled within each place, and each place keeps its total
// weight, so a place's weight is the product of the scans' likelihoods over
// its particles since it was found, as Bayes' rule has it. The places within
// `margin` nats of the best share the particles equally: a place's weight is
// a sum over its particles, and in log space the sum over a few spread ones
// falls tens of nats short of one over many (541 beams at 0.05 each: with
// shares by weight and a floor, the twin of a symmetric room fell 50 nats
// behind in two scans, 11 particles against 916), so unequal counts would
// decide by sampling alone. A place further behind gets its share by weight,
// as before, and is gone. (The filter also weighs a scan only after the robot
// moved, particle_filter.hpp: the same view again is no new evidence; and it
// scores each place at its best pose nearby, rescore_places: a sum over a
// place's particles depends on how near the best pose its cloud happens to be.)
#pragma once

#include <cstddef>
#include <optional>
#include <random>
#include <vector>

#include "common/geometry/se2.hpp"

namespace slamer {

struct Particle {
  Pose2 pose;
  double log_weight = 0.0;
};

// A group of particles within `radius` and `turn` of its seed, its most
// likely particle; `log_weight` is the group's total (the set's log weights
// normalized to sum to one).
struct Place {
  Pose2 seed;
  double log_weight = 0.0;
  std::vector<std::size_t> members;  // indices into the set
};

struct PlaceOptions {
  double radius = 1.0;         // [m] a particle this close to a seed (and within `turn`) is of its place
  double turn = 0.5;           // [rad]
  std::size_t max_places = 8;  // the places of most weight kept; the others' particles are of no place
  double margin = 50.0;        // [nats] a place this far behind the best is a rival no more
};

// Systematic (low-variance) resampling: `count` draws from set[indices] by
// their weights exp(log_weight - reference), one random offset and evenly
// spaced pointers, appended to `out` each with log weight `log_weight`.
// `total`: those weights' sum where known (1 for a normalized set and
// reference 0), else they are summed.
void systematic_draw(const std::vector<Particle>& set, const std::vector<std::size_t>& indices, double reference,
                     std::optional<double> total, std::size_t count, double log_weight, std::mt19937& rng,
                     std::vector<Particle>* out);

// Places of `set` (log weights normalized), the most likely first: each
// particle, in order of weight, joins the earliest place whose seed it is
// close to, or seeds a new one; the max_places of most weight are kept, the
// particles of the others are of no place.
std::vector<Place> places_of(const std::vector<Particle>& set, const PlaceOptions& options);

// The places within options.margin of the best (the best included).
std::vector<const Place*> rivals_in(const std::vector<Place>& places, const PlaceOptions& options);

// Sets each place's total weight to totals[k] (places[k], in order), its
// particles keeping their weights relative to each other. The particles of
// no place are left as they are.
void rescore_places(std::vector<Particle>* set, const std::vector<Place>& places, const std::vector<double>& totals);

// `n` particles from `set` (log weights normalized): the rest (places
// further than the margin behind the best, particles of no place) their
// share of n by weight, by systematic resampling; each place of `places`
// within the margin an equal part of the others, drawn by systematic
// resampling from its own particles, each with the place's weight divided
// equally.
std::vector<Particle> resample_keeping_places(const std::vector<Particle>& set, const std::vector<Place>& places,
                                              const PlaceOptions& options, std::size_t n, std::mt19937& rng);

}  // namespace slamer

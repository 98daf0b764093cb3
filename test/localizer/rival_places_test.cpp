// Places of a particle cloud and the resampling that keeps them (rival_places.hpp).
#include "localizer/rival_places.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

namespace slamer {
namespace {

// `count` particles around `at` (within 0.1 m), each with log weight `log_weight`.
void add(std::vector<Particle>* set, const Pose2& at, int count, double log_weight) {
  for (int k = 0; k < count; ++k) {
    const double d = 0.1 * static_cast<double>(k % 5) / 5.0;
    set->push_back({{at.x + d, at.y - d, at.theta}, log_weight});
  }
}

// Total weight (linear) of the particles within 1 m of `at`.
double weight_near(const std::vector<Particle>& set, const Pose2& at) {
  double sum = 0.0;
  for (const Particle& p : set) {
    if (std::hypot(p.pose.x - at.x, p.pose.y - at.y) < 1.0) {
      sum += std::exp(p.log_weight);
    }
  }
  return sum;
}

int count_near(const std::vector<Particle>& set, const Pose2& at) {
  int n = 0;
  for (const Particle& p : set) {
    n += std::hypot(p.pose.x - at.x, p.pose.y - at.y) < 1.0 ? 1 : 0;
  }
  return n;
}

const Pose2 kA{0.0, 0.0, 0.0};
const Pose2 kB{6.0, 0.0, 0.0};   // a look-alike 6 m along
const Pose2 kC{0.0, 10.0, 1.0};  // far behind

// 100 particles at A carrying 0.9 of the weight, 100 at B 0.1, 10 at C e^-80 of A's each.
std::vector<Particle> three_places() {
  std::vector<Particle> set;
  add(&set, kA, 100, std::log(0.9 / 100.0));
  add(&set, kB, 100, std::log(0.1 / 100.0));
  add(&set, kC, 10, std::log(0.9 / 100.0) - 80.0);
  return set;
}

TEST(RivalPlaces, ParticlesGroupAroundTheMostLikelyOnesTheHeaviestPlaceFirst) {
  const std::vector<Place> places = places_of(three_places(), PlaceOptions{});
  ASSERT_EQ(places.size(), 3u);
  EXPECT_NEAR(places[0].seed.x, kA.x, 0.1);
  EXPECT_NEAR(places[1].seed.x, kB.x, 0.1);
  EXPECT_NEAR(places[2].seed.y, kC.y, 0.1);
  EXPECT_EQ(places[0].members.size(), 100u);
  EXPECT_EQ(places[1].members.size(), 100u);
  EXPECT_EQ(places[2].members.size(), 10u);
  EXPECT_NEAR(places[0].log_weight, std::log(0.9), 1e-9);
  EXPECT_NEAR(places[1].log_weight, std::log(0.1), 1e-9);
  // Within the margin (50 nats): A and B; C is 80 behind.
  EXPECT_EQ(rivals_in(places, PlaceOptions{}).size(), 2u);
}

TEST(RivalPlaces, AParticleBeyondTheLastPlaceIsNoPlacesAndAHeadingApartIsAnotherPlace) {
  std::vector<Particle> set;
  add(&set, kA, 10, std::log(0.05));
  add(&set, {kA.x, kA.y, 2.0}, 10, std::log(0.04));  // the same spot, facing elsewhere
  add(&set, kB, 10, std::log(0.01));
  PlaceOptions options;
  options.max_places = 2;
  const std::vector<Place> places = places_of(set, options);
  ASSERT_EQ(places.size(), 2u);
  EXPECT_NEAR(places[1].seed.theta, 2.0, 1e-9);
  EXPECT_EQ(places[0].members.size() + places[1].members.size(), 20u);
}

TEST(RivalPlaces, ResamplingSharesTheParticlesEquallyAmongRivalsAndKeepsEachOnesWeight) {
  const std::vector<Particle> set = three_places();
  const PlaceOptions options;
  std::mt19937 rng(7);
  const std::vector<Particle> next = resample_keeping_places(set, places_of(set, options), options, 201, rng);
  ASSERT_EQ(next.size(), 201u);
  // By weight B would get 20 of 201: rivals get equal parts, the best the odd one.
  EXPECT_EQ(count_near(next, kB), 100);
  EXPECT_EQ(count_near(next, kA), 101);
  EXPECT_EQ(count_near(next, kC), 0) << "80 nats behind: no rival, its share of 200 rounds to none";
  // Each place keeps its weight: B is still 0.1, as the evidence so far says, not 100/201.
  const double total = weight_near(next, kA) + weight_near(next, kB);
  EXPECT_NEAR(weight_near(next, kA) / total, 0.9, 1e-9);
  EXPECT_NEAR(weight_near(next, kB) / total, 0.1, 1e-9);
}

TEST(RivalPlaces, RescoringSetsEachPlacesTotalAndKeepsItsParticlesRelativeWeights) {
  std::vector<Particle> set = three_places();
  set[0].log_weight += std::log(3.0);  // within A, one particle three times the others
  const std::vector<Place> places = places_of(set, PlaceOptions{});
  ASSERT_EQ(places.size(), 3u);
  const std::vector<Particle> before = set;
  // A and B swap totals; C is not given one and is left as it was.
  rescore_places(&set, places, {std::log(0.1), std::log(0.9)});
  double a = 0.0;
  double b = 0.0;
  for (const std::size_t i : places[0].members) {
    a += std::exp(set[i].log_weight);
  }
  for (const std::size_t i : places[1].members) {
    b += std::exp(set[i].log_weight);
  }
  EXPECT_NEAR(a, 0.1, 1e-12);
  EXPECT_NEAR(b, 0.9, 1e-12);
  EXPECT_NEAR(set[0].log_weight - set[1].log_weight, std::log(3.0), 1e-12);
  for (const std::size_t i : places[2].members) {
    EXPECT_EQ(set[i].log_weight, before[i].log_weight);
  }
  for (std::size_t i = 0; i < set.size(); ++i) {
    EXPECT_EQ(set[i].pose.x, before[i].pose.x);
  }
}

TEST(RivalPlaces, WithOnePlaceItIsOrdinarySystematicResampling) {
  std::vector<Particle> set;
  add(&set, kA, 50, std::log(0.5 / 50.0));
  set.push_back({{0.5, 0.5, 0.0}, std::log(0.5)});  // one particle with half the weight
  const PlaceOptions options;
  std::mt19937 rng(3);
  const std::vector<Place> places = places_of(set, options);
  ASSERT_EQ(places.size(), 1u);
  const std::vector<Particle> next = resample_keeping_places(set, places, options, 100, rng);
  ASSERT_EQ(next.size(), 100u);
  int heavy = 0;
  for (const Particle& p : next) {
    heavy += p.pose.x == 0.5 && p.pose.y == 0.5 ? 1 : 0;
    EXPECT_NEAR(p.log_weight, std::log(1.0 / 100.0), 1e-9);
  }
  EXPECT_EQ(heavy, 50);  // systematic: exactly its share

  // No places given: one place of them all.
  std::mt19937 other(3);
  const std::vector<Particle> without = resample_keeping_places(set, {}, options, 100, other);
  ASSERT_EQ(without.size(), 100u);
  int heavy_without = 0;
  for (const Particle& p : without) {
    heavy_without += p.pose.x == 0.5 && p.pose.y == 0.5 ? 1 : 0;
    EXPECT_NEAR(p.log_weight, std::log(1.0 / 100.0), 1e-9);
  }
  EXPECT_EQ(heavy_without, 50);
  EXPECT_TRUE(rivals_in({}, options).empty());
}

}  // namespace
}  // namespace slamer

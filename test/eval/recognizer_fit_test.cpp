// The recognizer's rule fit and the recognition model's temperature, on
// labelled objects made up here (the full path, simulated worlds, runs in
// calibrate_process_test.cpp).
#include <gtest/gtest.h>

#include <random>

#include "tools/eval/recognizer_fit.hpp"

namespace slamer {
namespace {

const std::vector<std::string> kClasses{"door", "wall", "fence"};

// `n` objects in `bin` whose truth is class 0 with probability `p0`, else 1 or 2 evenly.
void add_objects(std::vector<LabelledObject>* objects, int bin, int n, double p0, std::mt19937* random) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double r = u(*random);
    objects->push_back({bin, r < p0 ? 0 : (r < p0 + (1.0 - p0) / 2.0 ? 1 : 2), false});
  }
}

TEST(RecognizerFit, RulesAreTheBinsClassFrequencies) {
  std::vector<LabelledObject> objects;
  for (int i = 0; i < 8; ++i) {
    objects.push_back({3, 0, false});
  }
  objects.push_back({3, 1, false});
  objects.push_back({3, 2, false});
  objects.push_back({7, 2, false});
  const FittedRules fitted = fit_rules(objects, kClasses, 0.5);
  ASSERT_EQ(fitted.rules.size(), 2u);  // only the bins that had objects
  EXPECT_EQ(fitted.objects, (std::vector<int64_t>{10, 1}));
  // (8 + 0.5) / (10 + 1.5), (1 + 0.5) / 11.5
  EXPECT_NEAR(fitted.rules[0].probs.at("door"), 8.5 / 11.5, 1e-12);
  EXPECT_NEAR(fitted.rules[0].probs.at("wall"), 1.5 / 11.5, 1e-12);
  EXPECT_NEAR(fitted.rules[1].probs.at("fence"), 1.5 / 2.5, 1e-12);
  EXPECT_EQ(fitted.right, 9);
  EXPECT_TRUE(fitted.probs[0].empty());
  ASSERT_EQ(fitted.probs[3].size(), 3u);
  const std::vector<ClassRule> bins = bin_rules();
  EXPECT_EQ(fitted.rules[0].min_length, bins[3].min_length);
  EXPECT_EQ(fitted.rules[0].max_coverage, bins[3].max_coverage);
  const std::string yaml = rules_yaml(fitted, kClasses);
  EXPECT_NE(yaml.find("on 11 objects"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("door: 0.739"), std::string::npos) << yaml;
  // How often each class occurs among the fitted objects: the bins' probabilities weighted by their counts.
  ASSERT_EQ(fitted.class_prior.size(), 3u);
  EXPECT_NEAR(fitted.class_prior[0], (10.0 * 8.5 / 11.5 + 1.0 * 0.5 / 2.5) / 11.0, 1e-12);
  EXPECT_NEAR(fitted.class_prior[2], (10.0 * 1.5 / 11.5 + 1.0 * 1.5 / 2.5) / 11.0, 1e-12);
  EXPECT_NEAR(fitted.class_prior[0] + fitted.class_prior[1] + fitted.class_prior[2], 1.0, 1e-12);
  const std::string prior_yaml = training_prior_yaml(fitted, kClasses);
  EXPECT_NE(prior_yaml.find("    training_prior:\n      door: 0.69\n"), std::string::npos) << prior_yaml;
}

TEST(RecognizerFit, TemperatureIsOneWhereTheRulesHoldAndBelowWhereTheyPromiseTooMuch) {
  std::mt19937 random(5);
  std::vector<LabelledObject> training;
  add_objects(&training, 0, 4000, 0.9, &random);
  add_objects(&training, 1, 4000, 0.2, &random);
  const FittedRules rules = fit_rules(training, kClasses, 0.5);
  // Held-out objects like the training ones: the rules' confidence is right.
  std::vector<LabelledObject> alike;
  add_objects(&alike, 0, 4000, 0.9, &random);
  add_objects(&alike, 1, 4000, 0.2, &random);
  EXPECT_NEAR(fit_temperature({{&rules, &alike}}, 0.001), 1.0, 0.1);
  // Another building: where the rules say 90 % door, 50 % are.
  std::vector<LabelledObject> unlike;
  add_objects(&unlike, 0, 4000, 0.5, &random);
  add_objects(&unlike, 1, 4000, 0.2, &random);
  const double t = fit_temperature({{&rules, &unlike}}, 0.001);
  EXPECT_LT(t, 0.7);
  EXPECT_GT(t, 0.05);
  // Bins the rules never saw tell nothing.
  std::vector<LabelledObject> unseen{{9, 0, false}, {-1, 1, false}};
  EXPECT_NEAR(fit_temperature({{&rules, &alike}, {&rules, &unseen}}, 0.001), fit_temperature({{&rules, &alike}}, 0.001),
              1e-12);
}

}  // namespace
}  // namespace slamer

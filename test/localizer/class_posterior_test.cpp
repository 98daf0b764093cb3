// SLAMER's class posteriors (paper Eq. (4) with Eqs. (7)-(8)) of single objects
// in the small world: the training prior divided out, free space's margins, a
// spatial line's ends, objects the map lacks, and a physical line's farthest sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "localizer/particle_filter.hpp"
#include "localizer/recognition_model.hpp"
#include "recognizer/line_recognizer.hpp"
#include "test/localizer/options_error.hpp"
#include "test/localizer/small_world.hpp"

namespace slamer {
namespace {

// SLAMER's class posterior of one object, given by its ends in the map frame,
// from a filter settled at `truth` in the small world.
class ObjectPosterior {
 public:
  explicit ObjectPosterior(const Pose2& truth) : truth_(truth), sensor_(compose(truth, w_.robot.lidar.mount)) {}

  std::size_t index(const std::string& name) const {
    return static_cast<std::size_t>(std::find(classes_.begin(), classes_.end(), name) - classes_.begin());
  }
  // The recognizer's probabilities: `probs` for the classes named, `rest` for the others.
  LineObject object(LineKind kind, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                    const std::map<std::string, float>& probs, float rest) const {
    LineObject o;
    o.kind = kind;
    o.start = transform_point(inverse(sensor_), from);
    o.end = transform_point(inverse(sensor_), to);
    o.probs.assign(classes_.size(), rest);
    for (const auto& [name, p] : probs) {
      o.probs[index(name)] = p;
    }
    return o;
  }
  std::vector<float> posterior(const LocalizerOptions& options, const LineObject& o) const {
    ParticleFilter filter(w_.map, options, w_.robot.lidar.mount);
    filter.initialize(truth_, {0.01, 0.01, 0.005});
    LineObjectSet objects;
    objects.class_names = classes_;
    objects.objects = {o};
    const UpdateResult result = filter.update(w_.scan_at(truth_), &objects);
    EXPECT_EQ(result.semantic.objects.size(), 1u);
    return result.semantic.objects.at(0).probs;
  }
  std::string label(const LocalizerOptions& options, const LineObject& o) const {
    const std::vector<float> p = posterior(options, o);
    return classes_[static_cast<std::size_t>(std::max_element(p.begin(), p.end()) - p.begin())];
  }
  double log_odds(const std::vector<float>& p, const char* a, const char* b) const {
    return std::log(static_cast<double>(p[index(a)]) / static_cast<double>(p[index(b)]));
  }

 private:
  const SmallWorld w_;
  const std::vector<std::string> classes_ = RecognizerOptions{}.classes;
  const Pose2 truth_;
  const Pose2 sensor_;
};

LocalizerOptions slamer_filter(SpatialLineEnds ends) {
  LocalizerOptions options;
  options.mode = LocalizerMode::kSlamer;
  options.particles = 50;
  options.slamer.spatial_line_ends = ends;
  return options;
}

// The training prior much as the shipped one: no-entry lines rare, free space common.
void set_training_prior(LocalizerOptions* options) {
  for (const std::string& name : RecognizerOptions{}.classes) {
    options->slamer.training_prior[name] = 0.03;
  }
  options->slamer.training_prior["free_space"] = 0.27;
  options->slamer.training_prior["no_entry_line"] = 0.002;
  options->slamer.training_prior["others"] = 0.59;
}

// A spatial line from x 7.2 to 8.8 at height y, seen facing the small room's no-entry line (7..9, 5);
// the recognizer cannot see such a line and says free space.
LineObject across_the_no_entry_line(const ObjectPosterior& f, double y) {
  return f.object(LineKind::kSpatial, {7.2, y}, {8.8, y}, {{"free_space", 0.97f}, {"no_entry_line", 0.003f}}, 0.004f);
}
constexpr Pose2 kFacingTheNoEntryLine{8.0, 3.0, std::numbers::pi / 2};

// The recognizer cannot see a no-entry line: over the gap it says free space
// (0.97), and no-entry line only at 0.003 because such lines were rare where it
// was fitted. With that training prior divided out (Eq. (8) is given the
// likelihood, the map prior takes the prior's place), the map's no-entry line
// decides; without it the same object stays free space.
TEST(ParticleFilter, AnObjectOnTheMapsNoEntryLineIsOneOnceTheTrainingPriorIsDividedOut) {
  const ObjectPosterior f(kFacingTheNoEntryLine);
  LocalizerOptions options = slamer_filter(SpatialLineEnds::kScored);
  options.slamer.training_prior.clear();
  EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 5.0)), "free_space");
  set_training_prior(&options);
  EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 5.0)), "no_entry_line");
  // Raised to the power 0 the prior divides nothing out.
  options.slamer.training_prior_exponent = 0.0;
  EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 5.0)), "free_space");
  options.slamer.training_prior_exponent = 1.0;
  // Elsewhere, on free floor far from any classed cell, the same object is free space still.
  EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 3.8)), "free_space");
}

// A no-entry line is invisible, so its recognized line lies where the walls it
// is anchored to end, beside the map's line. 0.25 m beside it, floor 0.45 m
// clear of it is as near as the line itself and the recognizer's free space
// wins; with a margin of 0.7 m for no-entry lines the map's line does. Far from
// it the same object is free space either way.
TEST(ParticleFilter, AMarginOfItsOwnForNoEntryLinesHoldsALineBesideTheMapsOne) {
  const ObjectPosterior f(kFacingTheNoEntryLine);
  for (const SpatialLineEnds ends : {SpatialLineEnds::kScored, SpatialLineEnds::kLeftOut}) {
    LocalizerOptions options = slamer_filter(ends);
    set_training_prior(&options);
    options.slamer.free_space_class_margins.clear();
    EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 5.0)), "no_entry_line");
    EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 4.75)), "free_space");
    options.slamer.free_space_class_margins["no_entry_line"] = 0.7;
    EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 4.75)), "no_entry_line");
    EXPECT_EQ(f.label(options, across_the_no_entry_line(f, 3.8)), "free_space");
  }
}

// Seen from the left room's middle: a spatial line across the room at y 4.5, from
// its left wall to the wall between the rooms, and the doorway between the rooms
// (the map's door, y 2.5..3.5 at x 6).
constexpr Pose2 kLeftRoom{3.0, 3.0, std::numbers::pi / 2};
const Eigen::Vector2d kGapFrom{0.05, 4.5}, kGapTo{5.95, 4.5};
const Eigen::Vector2d kDoorwayFrom{6.0, 2.55}, kDoorwayTo{6.0, 3.45};

// A spatial line's ends lie on the walls that bound its gap, never in free space.
// Scored with them, free space's representative distance across an open floor
// was nearly 0.3 m (each end about 0.45 m from floor clear of classed cells, the
// middle 0), 2 prior sigmas: a gap beside a mapped door came out nearer the door
// than free space. Scored by the samples between the ends it is 0: free space
// gains d^2 / (2 sigma^2), at most 2 nats, against every other class, whose
// terms do not change; a doorway's middle lies on the door, so it stays a door.
TEST(ParticleFilter, FreeSpaceIsScoredBetweenTheEndsOfAGapSoAGapBetweenWallsIsFreeSpace) {
  const ObjectPosterior f(kLeftRoom);
  const std::map<std::string, float> leaning_free{{"free_space", 0.55f}, {"open_door", 0.39f}};
  const LineObject gap = f.object(LineKind::kSpatial, kGapFrom, kGapTo, leaning_free, 0.01f);
  // The ends' rule alone: the unmapped objects' mixture would spread free space's gain over the classes.
  LocalizerOptions scored = slamer_filter(SpatialLineEnds::kScored);
  LocalizerOptions left_out = slamer_filter(SpatialLineEnds::kLeftOutForFreeSpace);
  scored.slamer.posterior_unmapped_probability = left_out.slamer.posterior_unmapped_probability = 0.0;
  const std::vector<float> before = f.posterior(scored, gap);
  const std::vector<float> after = f.posterior(left_out, gap);
  const double gain = f.log_odds(after, "free_space", "others") - f.log_odds(before, "free_space", "others");
  EXPECT_GT(gain, 1.5);  // 1.79: the ends 0.43 m from clear floor
  EXPECT_LE(gain, 2.0 + 1e-4);
  EXPECT_NEAR(f.log_odds(after, "open_door", "others"), f.log_odds(before, "open_door", "others"), 1e-4);
  EXPECT_GT(after[f.index("free_space")], 0.9f);
  const LineObject doorway = f.object(LineKind::kSpatial, kDoorwayFrom, kDoorwayTo, leaning_free, 0.01f);
  for (const SpatialLineEnds ends : {SpatialLineEnds::kScored, SpatialLineEnds::kLeftOutForFreeSpace}) {
    const std::vector<float> p = f.posterior(slamer_filter(ends), doorway);
    EXPECT_GT(p[f.index("open_door")], p[f.index("free_space")]) << static_cast<int>(ends);
  }
}

// kLeftOut scores every class of a spatial line by the samples between its ends:
// the gap between walls is free space even where the recognizer leans to a door,
// and the doorway, whose middle lies on the map's door, stays an open door.
// Physical lines keep their ends.
TEST(ParticleFilter, SpatialLinesEndsLeftOutAGapBetweenWallsIsFreeSpaceAndTheDoorwayADoor) {
  const ObjectPosterior f(kLeftRoom);
  const std::map<std::string, float> leaning_door{{"free_space", 0.39f}, {"open_door", 0.55f}};
  const auto free_vs_door = [&](const std::vector<float>& p) { return f.log_odds(p, "free_space", "open_door"); };
  const LineObject gap = f.object(LineKind::kSpatial, kGapFrom, kGapTo, leaning_door, 0.01f);
  const std::vector<float> scored = f.posterior(slamer_filter(SpatialLineEnds::kScored), gap);
  const std::vector<float> left_out = f.posterior(slamer_filter(SpatialLineEnds::kLeftOut), gap);
  EXPECT_GT(free_vs_door(left_out) - free_vs_door(scored), 1.5);  // the ends 0.43 m from clear floor
  EXPECT_GT(left_out[f.index("free_space")], 0.9f);
  const LineObject physical = f.object(LineKind::kPhysical, kGapFrom, kGapTo, leaning_door, 0.01f);
  EXPECT_NEAR(free_vs_door(f.posterior(slamer_filter(SpatialLineEnds::kLeftOut), physical)),
              free_vs_door(f.posterior(slamer_filter(SpatialLineEnds::kScored), physical)), 1e-4);
  const LineObject doorway = f.object(LineKind::kSpatial, kDoorwayFrom, kDoorwayTo, leaning_door, 0.01f);
  EXPECT_LT(free_vs_door(f.posterior(slamer_filter(SpatialLineEnds::kLeftOut), doorway)), -1.0);
}

TEST(RecognitionModel, AnObjectTheMapLacksFollowsTheBaseRates) {
  // Two classes, the recognition terms log q = (log 2, log 1), the map prior flat (p_map 1/2 each),
  // base rates (0.1, 0.9): with u = 0.5, log 2 + log(0.25 + 0.05) and log 1 + log(0.25 + 0.45).
  const std::vector<double> log_recognition{std::log(2.0), 0.0};
  const std::vector<double> flat{log_recognition[0] - 4.5, log_recognition[1] - 4.5};
  const std::vector<double> mixed = with_unmapped_objects(flat, log_recognition, {0.1, 0.9}, 0.5);
  ASSERT_EQ(mixed.size(), 2u);
  EXPECT_NEAR(mixed[0], std::log(0.6), 1e-12);
  EXPECT_NEAR(mixed[1], std::log(0.7), 1e-12);
  // u = 0: the terms as they were; no base rates: uniform ones.
  EXPECT_EQ(with_unmapped_objects(flat, log_recognition, {0.1, 0.9}, 0.0), flat);
  const std::vector<double> uniform = with_unmapped_objects(flat, log_recognition, {}, 0.5);
  EXPECT_NEAR(uniform[0], std::log(2.0 * 0.5), 1e-12);
  EXPECT_NEAR(uniform[1], std::log(0.5), 1e-12);
  // Where the map has a class, the mixture's share is all the others get: u times their base rate.
  const std::vector<double> mapped{log_recognition[0], log_recognition[1] - 50.0};
  const std::vector<double> m = with_unmapped_objects(mapped, log_recognition, {0.1, 0.9}, 0.01);
  EXPECT_NEAR(m[0], std::log(2.0 * (0.99 + 0.001)), 1e-9);
  EXPECT_NEAR(m[1], std::log(0.01 * 0.9), 1e-9);
}

// The shipped training prior (config/localizer.yaml): closed doors 0.86 % of the training objects.
void set_shipped_training_prior(LocalizerOptions* options) {
  options->slamer.training_prior = {
      {"open_door", 0.0464}, {"closed_door", 0.00864},  {"open_glass_door", 0.0184}, {"closed_glass_door", 0.0322},
      {"fence", 0.0279},     {"no_entry_line", 0.0019}, {"free_space", 0.273},       {"others", 0.591}};
}

// Furniture the map lacks, in the middle of the left room: every class but free
// space is far from its cells, so the map prior cannot tell them apart, and the
// recognizer does not say free space. Its output is one seen on a generated
// world's added box (others 0.69, fence 0.13, closed door 0.105). With the
// training prior divided out, the rarest class, a closed door, won; with the
// object possibly not the map's (u 0.01, shipped), others, as the recognizer says.
TEST(ParticleFilter, FurnitureTheMapLacksIsNotTakenForTheRarestClass) {
  const ObjectPosterior f(kLeftRoom);
  const LineObject box = f.object(
      LineKind::kPhysical, {2.5, 3.8}, {3.5, 3.8},
      {{"others", 0.691f}, {"fence", 0.126f}, {"closed_door", 0.105f}, {"closed_glass_door", 0.077f}}, 0.00025f);
  LocalizerOptions options = slamer_filter(SpatialLineEnds::kLeftOut);
  set_shipped_training_prior(&options);
  options.slamer.posterior_unmapped_probability = 0.0;
  EXPECT_EQ(f.label(options, box), "closed_door");
  options.slamer.posterior_unmapped_probability = LocalizerOptions{}.slamer.posterior_unmapped_probability;
  EXPECT_EQ(f.label(options, box), "others");
  // A no-entry line where the map has one is one still: there the map outweighs the base rates.
  const ObjectPosterior g(kFacingTheNoEntryLine);
  EXPECT_EQ(g.label(options, across_the_no_entry_line(g, 5.0)), "no_entry_line");  // 0.71, free space 0.27
}

// The recognizer cannot tell a closed leaf flush with its wall from the wall:
// on a generated world's closed door it said others 0.976, closed door 0.013.
// The small world's door (closed in the map, x 6, y 2.5..3.5) with that output,
// its line ending where the walls begin: by the mean of its samples the ends
// put it almost as near the walls as the door and the recognizer decided
// (others); by the farthest sample its middle is 0.45 m (saturated) from any
// wall, and it is the closed door it is. A wall that ends at the door, and a
// line along the whole wall with the door in its middle, stay walls.
TEST(ParticleFilter, AClosedDoorFlushWithItsWallsIsOneWhereTheMapHasADoor) {
  const ObjectPosterior f(kLeftRoom);
  const std::map<std::string, float> like_a_wall{{"others", 0.976f}, {"closed_door", 0.013f}, {"fence", 0.01f}};
  const LineObject leaf = f.object(LineKind::kPhysical, {5.97, 2.52}, {5.97, 3.48}, like_a_wall, 0.0002f);
  const LineObject beside = f.object(LineKind::kPhysical, {5.95, 3.52}, {5.95, 5.0}, like_a_wall, 0.0002f);
  const LineObject along = f.object(LineKind::kPhysical, {5.95, 1.0}, {5.95, 5.0}, like_a_wall, 0.0002f);
  LocalizerOptions options = slamer_filter(SpatialLineEnds::kLeftOut);
  set_shipped_training_prior(&options);
  options.slamer.physical_line_distance = PhysicalLineDistance::kMean;
  EXPECT_EQ(f.label(options, leaf), "others");
  EXPECT_EQ(f.label(options, beside), "others");
  EXPECT_EQ(f.label(options, along), "others");
  options.slamer.physical_line_distance = PhysicalLineDistance::kFarthest;
  const std::vector<float> p = f.posterior(options, leaf);
  EXPECT_GT(f.log_odds(p, "closed_door", "others"), 1.5);     // 4.5 nats of map prior against 2.2 of recognizer
  EXPECT_GT(f.log_odds(p, "closed_door", "open_door"), 3.0);  // one map class: the recognizer decides (3.4)
  EXPECT_EQ(f.label(options, beside), "others");
  EXPECT_EQ(f.label(options, along), "others");
  // The particle weights keep the mean: the filter's estimate is the same to the bit either way.
  LocalizerOptions mean = options;
  mean.slamer.physical_line_distance = PhysicalLineDistance::kMean;
  const SmallWorld w;
  LineObjectSet objects;
  objects.class_names = RecognizerOptions{}.classes;
  objects.objects = {leaf, beside};
  std::vector<Pose2> estimates;
  for (const LocalizerOptions& o : {options, mean}) {
    ParticleFilter filter(w.map, o, w.robot.lidar.mount);
    filter.initialize({3.1, 2.9, 1.5}, {0.1, 0.1, 0.05});
    estimates.push_back(filter.update(w.scan_at(kLeftRoom), &objects).estimate.pose);
  }
  EXPECT_EQ(estimates[0].x, estimates[1].x);
  EXPECT_EQ(estimates[0].y, estimates[1].y);
  EXPECT_EQ(estimates[0].theta, estimates[1].theta);
  EXPECT_GT(std::hypot(estimates[0].x - 3.1, estimates[0].y - 2.9), 0.0);  // and the scan moved it
}

TEST(LocalizerOptions, PhysicalLineDistanceIsMeanOrFarthest) {
  EXPECT_EQ(localizer_options_error("slamer: {physical_line_distance: mean}\n"), "");
  EXPECT_EQ(localizer_options_error("slamer: {physical_line_distance: farthest}\n"), "");
  const std::string error = localizer_options_error("slamer: {physical_line_distance: median}\n");
  EXPECT_NE(error.find("'slamer.physical_line_distance'"), std::string::npos) << error;
}

TEST(LocalizerOptions, PosteriorUnmappedProbabilityIsAProbabilityBelowOne) {
  EXPECT_EQ(localizer_options_error("slamer: {posterior_unmapped_probability: 0}\n"), "");
  for (const char* bad : {"1", "-0.1", "nan"}) {
    const std::string error =
        localizer_options_error(std::string("slamer: {posterior_unmapped_probability: ") + bad + "}\n");
    EXPECT_NE(error.find("'slamer.posterior_unmapped_probability'"), std::string::npos) << bad << ": " << error;
  }
}

}  // namespace
}  // namespace slamer

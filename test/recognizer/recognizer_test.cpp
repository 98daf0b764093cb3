#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "recognizer/line_recognizer.hpp"
#include "recognizer/orientation_histogram.hpp"
#include "recognizer/physical_lines.hpp"
#include "recognizer/spatial_lines.hpp"
#include "tools/sim/world.hpp"

namespace slamer {
namespace {

constexpr double kPi = std::numbers::pi;

LaserScan empty_scan(int beams) {
  LaserScan scan;
  scan.angle_min = -3.0 * kPi / 4.0;
  scan.angle_increment = beams > 1 ? 1.5 * kPi / (beams - 1) : 0.0;
  scan.range_min = 0.06f;
  scan.range_max = 30.0f;
  scan.ranges.assign(static_cast<std::size_t>(beams), std::numeric_limits<float>::infinity());
  return scan;
}

// Range along a beam to the line {p : n.p = c} (n unit), +inf if it never gets there.
float range_to_line(double angle, const Eigen::Vector2d& n, double c) {
  const double denominator = n.dot(Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  if (denominator <= 1e-9) {
    return std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(c / denominator);
}

// A scan of the world's geometry cast from `sensor`, without noise.
LaserScan cast_scan(const TrueWorld& world, const Pose2& sensor) {
  LaserScan scan = empty_scan(1081);
  std::mt19937 rng(1);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double r = world.cast({sensor.x, sensor.y}, sensor.theta + scan.angle(i), 30.0, 0.0, rng);
    scan.ranges[i] = std::isfinite(r) && r <= 30.0 ? static_cast<float>(r) : std::numeric_limits<float>::infinity();
  }
  return scan;
}

int count(const LineObjectSet& set, LineKind kind) {
  return static_cast<int>(
      std::count_if(set.objects.begin(), set.objects.end(), [kind](const LineObject& o) { return o.kind == kind; }));
}

void expect_normalized(const LineObjectSet& set) {
  for (const LineObject& o : set.objects) {
    ASSERT_EQ(o.probs.size(), set.class_names.size());
    double sum = 0.0;
    for (const float p : o.probs) {
      ASSERT_GE(p, 0.0f);
      sum += p;
    }
    EXPECT_NEAR(sum, 1.0, 1e-5);
  }
}

TEST(Recognizer, DegenerateScansGiveNoObjectsAndNoCrash) {
  const LineRecognizer recognizer{RecognizerOptions{}};
  EXPECT_TRUE(recognizer.recognize(empty_scan(0)).objects.empty());
  LaserScan one = empty_scan(1);
  one.ranges[0] = 2.0f;
  EXPECT_TRUE(recognizer.recognize(one).objects.empty());
  EXPECT_TRUE(recognizer.recognize(empty_scan(1081)).objects.empty());  // all +inf: no line at all
  LaserScan nan = empty_scan(1081);
  std::fill(nan.ranges.begin(), nan.ranges.end(), std::numeric_limits<float>::quiet_NaN());
  EXPECT_TRUE(recognizer.recognize(nan).objects.empty());
  LaserScan close = empty_scan(1081);
  std::fill(close.ranges.begin(), close.ranges.end(), -std::numeric_limits<float>::infinity());
  EXPECT_TRUE(recognizer.recognize(close).objects.empty());
  LaserScan broken = empty_scan(1081);
  broken.angle_increment = std::numeric_limits<double>::quiet_NaN();
  std::fill(broken.ranges.begin(), broken.ranges.end(), 2.0f);
  EXPECT_TRUE(recognizer.recognize(broken).objects.empty());
  const LineObjectSet result = recognizer.recognize(nan);
  EXPECT_EQ(result.class_names.size(), 8u);
  // A tiny angle increment once overflowed the spatial search's span (found by the fuzzer).
  LaserScan tiny = empty_scan(1081);
  tiny.angle_increment = 1e-23;
  std::fill(tiny.ranges.begin(), tiny.ranges.end(), 2.0f);
  EXPECT_NO_FATAL_FAILURE(recognizer.recognize(tiny));
}

TEST(Recognizer, StraightWallIsOneFullyCoveredPhysicalLine) {
  // A wall 2 m to the left (y = 2), seen between 30 and 150 deg.
  LaserScan scan = empty_scan(1081);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle(i);
    if (a > kPi / 6 && a < 5 * kPi / 6) {
      scan.ranges[i] = range_to_line(a, {0.0, 1.0}, 2.0);
    }
  }
  const LineObjectSet result = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  ASSERT_EQ(count(result, LineKind::kPhysical), 1);
  const LineObject& wall = result.objects.front();
  EXPECT_NEAR(wall.start.y(), 2.0, 0.01);
  EXPECT_NEAR(wall.end.y(), 2.0, 0.01);
  // Visible from 30 deg to the scan's last beam at 135 deg: x from 2 / tan(30) down to -2.
  EXPECT_NEAR(std::abs(wall.end.x() - wall.start.x()), 2.0 / std::tan(kPi / 6) + 2.0, 0.05);
  expect_normalized(result);
  // Fully covered: the rule for walls (others most likely).
  EXPECT_EQ(result.class_names[static_cast<std::size_t>(most_likely(wall.probs))], "others");
}

TEST(Recognizer, SupportIsCountedForEveryOrientation) {
  // The same wall rotated to many directions, including negative angles:
  // the published implementation walked the wrong way for those.
  const RecognizerOptions options;
  for (int deg = -170; deg <= 180; deg += 25) {
    const double t = deg * kPi / 180.0;
    const Eigen::Vector2d n(std::cos(t), std::sin(t));
    LaserScan scan = empty_scan(1081);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double a = scan.angle(i);
      if (std::abs(angle_diff(a, t)) < kPi / 3) {
        scan.ranges[i] = range_to_line(a, n, 3.0);
      }
    }
    const PreparedScan prepared = prepare_scan(scan);
    const std::vector<PhysicalLine> lines = refine_physical_lines(prepared, hough_segments(prepared, options), options);
    if (std::abs(angle_diff(t, kPi)) < kPi / 4 + 0.01) {
      continue;  // the wall lies behind the sensor's 270 deg
    }
    ASSERT_EQ(lines.size(), 1u) << deg << " deg";
    EXPECT_GT(lines[0].coverage, 0.95) << deg << " deg";
    EXPECT_GT(lines[0].points, 200) << deg << " deg";
  }
}

TEST(SegmentGeometry, DistanceIsRightOffTheAxes) {
  const Segment2 diagonal{{0.0, 0.0}, {2.0, 2.0}};
  EXPECT_NEAR(distance_to_segment({2.0, 0.0}, diagonal), std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(distance_to_segment({3.0, 3.0}, diagonal), std::sqrt(2.0), 1e-12);  // past the end
  EXPECT_NEAR(distance_to_segment({-1.0, 1.0}, {{0.0, 0.0}, {-2.0, 2.0}}), 0.0, 1e-12);
  EXPECT_NEAR(orientation_difference({{0, 0}, {1, 0}}, {{0, 0}, {-1, 0.01}}), 0.01, 1e-4);
}

TEST(OrientationHistogram, WrapsAtPi) {
  OrientationHistogram histogram(36);
  histogram.add(kPi - 0.01, 5.0);                      // 179.4 deg
  EXPECT_TRUE(histogram.agrees(0.01, 0.5));            // 0.6 deg: the same orientation
  EXPECT_TRUE(histogram.agrees(-0.01, 0.5));           // -0.6 deg folds to 179.4
  EXPECT_TRUE(histogram.agrees(2 * kPi - 0.01, 0.5));  // a direction and its opposite
  EXPECT_FALSE(histogram.agrees(kPi / 2, 0.5));
  EXPECT_FALSE(OrientationHistogram(36).agrees(0.0, 0.1));  // empty histogram agrees with nothing
}

TEST(Recognizer, CornerGivesTwoPerpendicularLines) {
  LaserScan scan = empty_scan(1081);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle(i);
    // Walls x = 3 and y = 2 meeting at (3, 2).
    const float to_x = range_to_line(a, {1.0, 0.0}, 3.0);
    const float to_y = range_to_line(a, {0.0, 1.0}, 2.0);
    if (a > -kPi / 3 && a < 2 * kPi / 3) {
      scan.ranges[i] = std::min(to_x, to_y);
    }
  }
  const LineObjectSet result = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  ASSERT_EQ(count(result, LineKind::kPhysical), 2);
  const Eigen::Vector2d d0 = result.objects[0].end - result.objects[0].start;
  const Eigen::Vector2d d1 = result.objects[1].end - result.objects[1].start;
  EXPECT_NEAR(std::abs(d0.normalized().dot(d1.normalized())), 0.0, 0.03);
  EXPECT_EQ(count(result, LineKind::kSpatial), 0);  // a closed corner has nowhere to pass
}

// A corridor wall with a 1 m doorway into a room behind it.
TrueWorld doorway_world() {
  SemanticMap map;
  map.geometry = {200, 200, 0.05, {-5.0, -5.0, 0.0}};
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  const auto wall = [&](double x0, double y0, double x1, double y1) {
    for (int y = 0; y < 200; ++y) {
      for (int x = 0; x < 200; ++x) {
        const Eigen::Vector2d c = map.geometry.cell_center(x, y);
        if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1) {
          map.occupancy[map.geometry.index(x, y)] = Occupancy::kOccupied;
        }
      }
    }
  };
  wall(-4.0, 1.5, -0.5, 1.55);  // corridor wall y = 1.5 with a gap from x = -0.5 to 0.5
  wall(0.5, 1.5, 4.0, 1.55);
  wall(-4.0, 4.0, 4.0, 4.05);    // the room's far wall
  wall(-4.0, -1.05, 4.0, -1.0);  // the other corridor wall
  return TrueWorld(map, WorldOptions{}, "test");
}

TEST(Recognizer, DoorwayWithARoomBehindIsOneSpatialLine) {
  const TrueWorld world = doorway_world();
  const LineObjectSet result = LineRecognizer{RecognizerOptions{}}.recognize(cast_scan(world, {0.3, 0.0, 0.0}));
  expect_normalized(result);
  std::vector<const LineObject*> doorways;
  for (const LineObject& o : result.objects) {
    const Eigen::Vector2d mid = (o.start + o.end) / 2.0;
    // Sensor at (0.3, 0): the doorway's centre (0, 1.5) is at (-0.3, 1.5) in the sensor frame.
    if (o.kind == LineKind::kSpatial && (mid - Eigen::Vector2d(-0.3, 1.5)).norm() < 0.3) {
      doorways.push_back(&o);
    }
  }
  ASSERT_EQ(doorways.size(), 1u) << "one doorway, one spatial line (no duplicates from ordered pairs)";
  EXPECT_NEAR((doorways[0]->end - doorways[0]->start).norm(), 1.0, 0.15);
  EXPECT_EQ(result.class_names[static_cast<std::size_t>(most_likely(doorways[0]->probs))], "open_door");
}

TEST(Recognizer, ResultDoesNotDependOnCandidateOrder) {
  const TrueWorld world = doorway_world();
  const LaserScan scan = cast_scan(world, {0.3, 0.2, 0.4});
  const RecognizerOptions options;
  const PreparedScan prepared = prepare_scan(scan);
  std::vector<Segment2> candidates = hough_segments(prepared, options);
  ASSERT_GT(candidates.size(), 2u);
  const std::vector<PhysicalLine> reference = refine_physical_lines(prepared, candidates, options);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    std::shuffle(candidates.begin(), candidates.end(), rng);
    for (Segment2& s : candidates) {
      if (rng() % 2 == 0) {
        std::swap(s.a, s.b);
      }
    }
    const std::vector<PhysicalLine> again = refine_physical_lines(prepared, candidates, options);
    ASSERT_EQ(again.size(), reference.size());
    for (std::size_t i = 0; i < again.size(); ++i) {
      EXPECT_NEAR((again[i].segment.a - reference[i].segment.a).norm(), 0.0, 1e-9);
      EXPECT_NEAR((again[i].segment.b - reference[i].segment.b).norm(), 0.0, 1e-9);
      EXPECT_EQ(again[i].points, reference[i].points);
    }
  }
  // Spatial merging too.
  OrientationHistogram histogram(options.histogram_bins);
  for (const PhysicalLine& l : reference) {
    const Eigen::Vector2d d = l.segment.b - l.segment.a;
    histogram.add(std::atan2(d.y(), d.x()), d.norm());
  }
  std::vector<SpatialLine> spatial = spatial_candidates(prepared, scan.angle_increment, histogram, options);
  const std::vector<SpatialLine> merged = merge_spatial_lines(spatial, options);
  std::reverse(spatial.begin(), spatial.end());
  const std::vector<SpatialLine> merged_reversed = merge_spatial_lines(spatial, options);
  ASSERT_EQ(merged.size(), merged_reversed.size());
  for (std::size_t i = 0; i < merged.size(); ++i) {
    EXPECT_EQ(merged[i].first_beam, merged_reversed[i].first_beam);
    EXPECT_EQ(merged[i].last_beam, merged_reversed[i].last_beam);
  }
}

TEST(Recognizer, NanBeamsAreIgnoredNotDrawn) {
  const TrueWorld world = doorway_world();
  LaserScan scan = cast_scan(world, {0.3, 0.0, 0.0});
  const LineObjectSet clean = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  for (std::size_t i = 0; i < scan.ranges.size(); i += 7) {
    scan.ranges[i] = std::numeric_limits<float>::quiet_NaN();
  }
  const LineObjectSet with_nan = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  EXPECT_EQ(count(with_nan, LineKind::kPhysical), count(clean, LineKind::kPhysical));
  EXPECT_GE(count(with_nan, LineKind::kSpatial), 1);
}

TEST(Recognizer, RangesBeyondTheImageStillMakeSpatialLinesButNoPixels) {
  // A wall 20 m away, outside the 12 m image: no physical line from Hough, no crash.
  LaserScan scan = empty_scan(1081);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.angle(i);
    if (std::abs(a) < kPi / 8) {
      scan.ranges[i] = range_to_line(a, {1.0, 0.0}, 20.0);
    }
  }
  scan.range_max = 80.0f;
  const LineObjectSet result = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  EXPECT_EQ(count(result, LineKind::kPhysical), 0);
}

TEST(Classify, RulesAreDataAndProbabilitiesSumToOne) {
  RecognizerOptions options;
  options.classes = {"gate", "wall", "gap"};
  options.rules = {{LineKind::kPhysical, 0.5, 1.0, 0.0, 1e9, {{"wall", 8.0}, {"gate", 2.0}}},
                   {LineKind::kSpatial, 0.0, 1.0, 0.0, 1e9, {{"gap", 1.0}}}};
  options.floor = 0.0;
  const std::vector<float> wall = classify(LineKind::kPhysical, 0.9, 2.0, options);
  EXPECT_NEAR(wall[1], 0.8, 1e-6);
  EXPECT_NEAR(wall[0], 0.2, 1e-6);
  EXPECT_NEAR(wall[2], 0.0, 1e-6);
  const std::vector<float> unmatched = classify(LineKind::kPhysical, 0.1, 2.0, options);
  EXPECT_NEAR(unmatched[0], 1.0 / 3, 1e-6);
  EXPECT_NEAR(classify(LineKind::kSpatial, 0.0, 1.0, options)[2], 1.0, 1e-6);
}

}  // namespace
}  // namespace slamer

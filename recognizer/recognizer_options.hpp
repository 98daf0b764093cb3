// Options of the line-object recognizer (paper Sec. VI-B), with defaults for
// the URM-40LC on the i-Cart mini. Every threshold the published
// implementation hard-codes is here, and the class rules are data.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "common/semantic/objects.hpp"

namespace slamer {

class ConfigReader;  // common/config/config_reader.hpp: the YAML reader stays out of this header

// Probabilities for objects whose features fall in a range; the first
// matching rule gives an object its class distribution.
struct ClassRule {
  LineKind kind = LineKind::kPhysical;
  double min_coverage = 0.0;  // physical: fraction of the length the scan points cover
  double max_coverage = 1.0;
  double min_length = 0.0;              // [m]
  double max_length = 1e9;              // [m]
  std::map<std::string, double> probs;  // unnormalized; classes not listed get `floor`
};

struct RecognizerOptions {
  // Scan image for the Hough transform.
  double image_resolution = 0.05;  // [m per pixel]
  double image_extent = 12.0;      // [m] the image covers [-extent, extent]^2 around the sensor
  // Probabilistic Hough transform (cv::HoughLinesP), in metres and radians.
  double hough_rho = 0.05;
  double hough_theta = 0.0175;  // 1 deg
  int hough_threshold = 12;     // votes
  double hough_min_length = 0.4;
  double hough_max_gap = 0.25;
  // Physical lines.
  double support_distance = 0.06;  // [m] a point this close to a segment supports it
  double coverage_step = 0.06;     // [m] each supporting point covers this much of the length
  double physical_min_length = 0.3;
  int physical_min_points = 5;
  double merge_angle = 0.087;    // [rad] (5 deg) near-duplicate segments are merged...
  double merge_distance = 0.12;  // [m] ...when this close
  // Orientation histogram of the physical lines (folded to [0, pi)).
  int histogram_bins = 36;
  double histogram_min_fraction = 0.15;  // of the largest (smoothed) bin, for a spatial line to agree
  // Spatial lines between pairs of scan points.
  double spatial_min_length = 0.6;
  double spatial_max_length = 2.5;
  double pass_margin = 0.15;       // [m] a beam passes a line when its point is this far beyond it
  double min_pass_fraction = 0.8;  // of the beams between the two end points
  int min_pass_beams = 3;
  // Classes and the rules that give objects their probabilities.
  std::vector<std::string> classes = paper_recognition_classes();
  double floor = 0.01;  // probability of classes a rule does not list, before normalizing
  std::vector<ClassRule> rules{
      {LineKind::kPhysical, 0.7, 1.0, 0.0, 1e9, {{"others", 0.6}, {"closed_door", 0.3}}},
      {LineKind::kPhysical, 0.0, 0.7, 0.0, 1e9, {{"fence", 0.4}, {"closed_glass_door", 0.35}, {"others", 0.15}}},
      {LineKind::kSpatial,
       0.0,
       1.0,
       0.7,
       1.4,
       {{"open_door", 0.45}, {"open_glass_door", 0.15}, {"no_entry_line", 0.15}, {"free_space", 0.2}}},
      {LineKind::kSpatial, 0.0, 1.0, 0.0, 1e9, {{"free_space", 0.5}, {"no_entry_line", 0.3}, {"open_door", 0.1}}},
  };
};
void read_options(const ConfigReader& reader, RecognizerOptions* options);

}  // namespace slamer

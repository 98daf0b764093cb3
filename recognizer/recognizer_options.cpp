#include "recognizer/recognizer_options.hpp"

#include "common/config/config_reader.hpp"

#include <algorithm>
#include <cmath>

namespace slamer {

void read_options(const ConfigReader& reader, RecognizerOptions* o) {
  reader.read("image_resolution", &o->image_resolution, in_range(0.005, 1.0));
  reader.read("image_extent", &o->image_extent, in_range(0.5, 100.0));
  reader.read("hough_rho", &o->hough_rho, positive());
  reader.read("hough_theta", &o->hough_theta, in_range(1e-4, 0.5));
  reader.read("hough_threshold", &o->hough_threshold, at_least(1));
  reader.read("hough_min_length", &o->hough_min_length, positive());
  reader.read("hough_max_gap", &o->hough_max_gap, non_negative());
  reader.read("support_distance", &o->support_distance, positive());
  reader.read("coverage_step", &o->coverage_step, positive());
  reader.read("physical_min_length", &o->physical_min_length, non_negative());
  reader.read("physical_min_points", &o->physical_min_points, at_least(2));
  reader.read("merge_angle", &o->merge_angle, in_range(0.0, 1.0));
  reader.read("merge_distance", &o->merge_distance, non_negative());
  reader.read("histogram_bins", &o->histogram_bins, in_range(4, 3600));
  reader.read("histogram_min_fraction", &o->histogram_min_fraction, probability());
  reader.read("spatial_min_length", &o->spatial_min_length, positive());
  reader.read("spatial_max_length", &o->spatial_max_length, positive());
  reader.read("pass_margin", &o->pass_margin, positive());
  reader.read("min_pass_fraction", &o->min_pass_fraction, probability());
  reader.read("min_pass_beams", &o->min_pass_beams, at_least(1));
  reader.read("classes", &o->classes);
  reader.read("floor", &o->floor, in_range(0.0, 1.0));
  if (o->spatial_max_length < o->spatial_min_length) {
    reader.fail("spatial_max_length", "must not be below spatial_min_length");
  }
  if (o->classes.empty()) {
    reader.fail("classes", "the class list is empty");
  }
  if (reader.has("rules")) {
    o->rules.clear();
    for (const ConfigReader& entry : reader.list("rules")) {
      ClassRule rule;
      std::string kind = "physical";
      entry.read_choice("kind", &kind, {"physical", "spatial"});
      rule.kind = kind == "physical" ? LineKind::kPhysical : LineKind::kSpatial;
      entry.read("min_coverage", &rule.min_coverage, probability());
      entry.read("max_coverage", &rule.max_coverage, probability());
      entry.read("min_length", &rule.min_length, non_negative());
      entry.read("max_length", &rule.max_length, positive());
      const ConfigReader probs = entry.section("probs");
      for (const std::string& name : probs.keys()) {
        if (std::find(o->classes.begin(), o->classes.end(), name) == o->classes.end()) {
          probs.fail(name, "'" + name + "' is not in classes");
        }
        double p = 0.0;
        probs.read(name, &p, non_negative());
        rule.probs[name] = p;
      }
      o->rules.push_back(rule);
    }
  }
}

}  // namespace slamer

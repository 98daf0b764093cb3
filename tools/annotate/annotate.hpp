// slamer-annotate-map's work (issue 15, "Your own robot and map"): paints the
// objects of an objects file (object_list.hpp) onto a map_server map a SLAM
// package made, and writes the semantic map the localizer's --map loads
// (common/map/semantic_map.hpp's map_server format with a `semantic:`
// section), plus a preview image to check it by eye.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/map/semantic_map.hpp"
#include "tools/annotate/object_list.hpp"

namespace slamer {

struct AnnotationSummary {
  std::vector<int64_t> cells_per_object;  // cells each object painted (before later objects painted over them)
  int64_t occupancy_changed = 0;          // cells whose occupancy an object set to something else
};

// The map with `list`'s class table: the map's labels carried over by class
// name, occupied cells without a label become `others`, then every object's
// cells get its class (and its occupancy, unless `keep`), in order.
SemanticMap annotate_map(const SemanticMap& map, const ObjectList& list, AnnotationSummary* summary = nullptr);

// Writes map.pgm (trinary: 0 occupied, 254 free, 205 unknown), semantic.png
// (class colours; 254 free, 205 unknown where no class) and map.yaml into
// `directory`, which must exist. `header` becomes a YAML comment line.
void write_semantic_map(const SemanticMap& map, const std::string& directory, const std::string& header);

// The map scaled up by a whole factor (up to 8, to about 1200 pixels):
// occupied labelled cells in their class colour, free labelled cells in a
// lighter tint of it, free cells white, unknown grey; each object's number
// (its index in the file) beside its first point. Above the map a legend band
// (kPreviewLegendTop + kPreviewLegendRow pixels per class), below it a 1 m
// scale bar.
constexpr int kPreviewLegendTop = 10;
constexpr int kPreviewLegendRow = 16;
cv::Mat render_preview(const SemanticMap& map, const ObjectList& list);

}  // namespace slamer

// The scans alone of the real 2D laser datasets in ../shared/datasets:
// CARMEN FLASER / ROBOTLASER1 lines, CMU 16-831 "L" lines and the Mines
// exp1.dat lines (dataset_records.hpp has every format's details). Plain or
// gzip files. Lines that do not parse are counted and skipped, never guessed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sensors/laser_scan.hpp"
#include "tools/datasets/dataset_records.hpp"

namespace slamer {

struct DatasetScans {
  std::vector<LaserScan> scans;
  int64_t bad_lines = 0;
};

// Parses one line; false if it is not a scan line of that format (or malformed).
bool parse_dataset_line(DatasetFormat format, const std::string& line, LaserScan* scan);

// Reads up to `max_scans` scans (0: all). Throws std::runtime_error if the file cannot be read.
DatasetScans read_dataset(const std::string& path, DatasetFormat format, std::size_t max_scans = 0);

}  // namespace slamer

// Readers of the real 2D laser datasets in ../shared/datasets (see each
// SOURCE.txt): CARMEN "FLASER" lines (180 beams from -90 deg, 1 deg apart,
// metres; aces saturates at 50 m, fr079 writes 81.91 m for no return), CMU
// 16-831 "L" lines (180 beams over 180 deg, centimetres, 8183/8191 = no
// return) and the Mines exp1.dat (682 beams over 240 deg, millimetres,
// 0 = no return). Plain or gzip files. Lines that do not parse are counted
// and skipped, never guessed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sensors/laser_scan.hpp"

namespace slamer {

enum class DatasetFormat { kCarmen, kCmu, kMines };

struct DatasetScans {
  std::vector<LaserScan> scans;
  int64_t bad_lines = 0;
};

// Parses one line; false if it is not a scan line of that format (or malformed).
bool parse_dataset_line(DatasetFormat format, const std::string& line, LaserScan* scan);

// Reads up to `max_scans` scans (0: all). Throws std::runtime_error if the file cannot be read.
DatasetScans read_dataset(const std::string& path, DatasetFormat format, std::size_t max_scans = 0);

}  // namespace slamer

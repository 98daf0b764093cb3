#include "tools/datasets/dataset_scans.hpp"

#include <zlib.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string_view>

namespace slamer {
namespace {

// Splits on spaces and tabs; reads numbers strictly (no partial tokens).
class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}
  bool next(std::string_view* token) {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) {
      ++pos_;
    }
    if (pos_ >= text_.size()) {
      return false;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != ' ' && text_[pos_] != '\t' && text_[pos_] != '\r') {
      ++pos_;
    }
    *token = text_.substr(start, pos_ - start);
    return true;
  }
  template <class T>
  bool number(T* value) {
    std::string_view token;
    if (!next(&token)) {
      return false;
    }
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), *value);
    return error == std::errc() && end == token.data() + token.size();
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

constexpr float kInf = std::numeric_limits<float>::infinity();

// Seconds since the epoch to microseconds; false for times no log can have
// (negative, or past the year 5000), which would not fit the conversion.
bool to_utime(double seconds, int64_t* utime) {
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > 1e11) {
    return false;
  }
  *utime = static_cast<int64_t>(seconds * 1e6);
  return true;
}

void set_geometry(LaserScan* scan, double angle_min, double angle_increment, float range_max) {
  scan->angle_min = angle_min;
  scan->angle_increment = angle_increment;
  scan->range_min = 0.02f;
  scan->range_max = range_max;
  scan->frame = "laser";
}

bool parse_carmen(Tokens& tokens, LaserScan* scan) {
  int n = 0;
  if (!tokens.number(&n) || n <= 0 || n > 10000) {
    return false;
  }
  set_geometry(scan, -std::numbers::pi / 2, std::numbers::pi / n, 80.0f);
  scan->ranges.resize(static_cast<std::size_t>(n));
  for (float& r : scan->ranges) {
    double value = 0.0;
    if (!tokens.number(&value) || !std::isfinite(value) || value < 0.0) {
      return false;
    }
    // aces saturates at 50 m and fr079 writes 81.91 m: both mean no return.
    r = value >= 49.99 ? kInf : static_cast<float>(value);
  }
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  double ox = 0.0;
  double oy = 0.0;
  double otheta = 0.0;
  double timestamp = 0.0;
  if (!tokens.number(&x) || !tokens.number(&y) || !tokens.number(&theta) || !tokens.number(&ox) ||
      !tokens.number(&oy) || !tokens.number(&otheta) || !tokens.number(&timestamp)) {
    return false;
  }
  return to_utime(timestamp, &scan->utime);
}

bool parse_cmu(Tokens& tokens, LaserScan* scan) {
  double pose[6];
  for (double& v : pose) {
    if (!tokens.number(&v)) {
      return false;
    }
  }
  set_geometry(scan, -std::numbers::pi / 2, std::numbers::pi / 180.0, 81.8f);
  scan->ranges.resize(180);
  for (float& r : scan->ranges) {
    int centimetres = 0;
    if (!tokens.number(&centimetres) || centimetres < 0) {
      return false;
    }
    r = centimetres >= 8183 ? kInf : static_cast<float>(centimetres) * 0.01f;
  }
  double timestamp = 0.0;
  if (!tokens.number(&timestamp)) {
    return false;
  }
  return to_utime(timestamp, &scan->utime);
}

bool parse_mines(Tokens& tokens, LaserScan* scan) {
  int64_t micros = 0;
  if (!tokens.number(&micros) || micros < 0) {
    return false;
  }
  // tok[1] unused, tok[2..3] wheel ticks, tok[4..23] other data, tok[24..705] ranges.
  for (int i = 1; i < 24; ++i) {
    std::string_view skip;
    if (!tokens.next(&skip)) {
      return false;
    }
  }
  constexpr int kBeams = 682;
  const double fov = 240.0 * std::numbers::pi / 180.0;
  set_geometry(scan, -fov / 2, fov / (kBeams - 1), 4.0f);
  scan->ranges.resize(kBeams);
  for (float& r : scan->ranges) {
    int millimetres = 0;
    if (!tokens.number(&millimetres) || millimetres < 0) {
      return false;
    }
    r = millimetres == 0 ? kInf : static_cast<float>(millimetres) * 0.001f;
  }
  scan->range_max = 5.6f;  // URG-04LX reads a little beyond its nominal 4 m
  scan->utime = micros;
  return true;
}

}  // namespace

bool parse_dataset_line(DatasetFormat format, const std::string& line, LaserScan* scan) {
  Tokens tokens(line);
  std::string_view first;
  switch (format) {
    case DatasetFormat::kCarmen:
      return tokens.next(&first) && first == "FLASER" && parse_carmen(tokens, scan);
    case DatasetFormat::kCmu:
      return tokens.next(&first) && first == "L" && parse_cmu(tokens, scan);
    case DatasetFormat::kMines:
      return parse_mines(tokens, scan);
  }
  return false;
}

DatasetScans read_dataset(const std::string& path, DatasetFormat format, std::size_t max_scans) {
  gzFile file = gzopen(path.c_str(), "rb");  // reads plain files too
  if (file == nullptr) {
    throw std::runtime_error("cannot open dataset " + path);
  }
  DatasetScans result;
  std::string line;
  char buffer[65536];
  while (max_scans == 0 || result.scans.size() < max_scans) {
    line.clear();
    bool got = false;
    while (gzgets(file, buffer, sizeof(buffer)) != nullptr) {
      got = true;
      line += buffer;
      if (!line.empty() && line.back() == '\n') {
        line.pop_back();
        break;
      }
    }
    if (!got) {
      break;
    }
    const bool is_scan_line =
        format == DatasetFormat::kMines || line.rfind(format == DatasetFormat::kCarmen ? "FLASER " : "L ", 0) == 0;
    if (!is_scan_line) {
      continue;
    }
    LaserScan scan;
    if (parse_dataset_line(format, line, &scan)) {
      scan.seq = static_cast<int64_t>(result.scans.size());
      result.scans.push_back(std::move(scan));
    } else {
      ++result.bad_lines;
    }
  }
  gzclose(file);
  return result;
}

}  // namespace slamer

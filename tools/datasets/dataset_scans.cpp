#include "tools/datasets/dataset_scans.hpp"

#include <stdexcept>

#include "tools/datasets/dataset_lines.hpp"

namespace slamer {

bool parse_dataset_line(DatasetFormat format, const std::string& line, LaserScan* scan) {
  DatasetRecord record;
  std::string error;
  if (!parse_dataset_record(format, line, &record, &error) || record.kind != RecordKind::kScan) {
    return false;
  }
  *scan = std::move(record.scan);
  return true;
}

DatasetScans read_dataset(const std::string& path, DatasetFormat format, std::size_t max_scans) {
  DatasetLineReader reader(path);
  DatasetScans result;
  std::string line;
  while ((max_scans == 0 || result.scans.size() < max_scans) && reader.next(&line)) {
    DatasetRecord record;
    std::string error;
    if (!parse_dataset_record(format, line, &record, &error)) {
      ++result.bad_lines;
    } else if (record.kind == RecordKind::kScan) {
      record.scan.seq = static_cast<int64_t>(result.scans.size());
      result.scans.push_back(std::move(record.scan));
    }
  }
  return result;
}

}  // namespace slamer

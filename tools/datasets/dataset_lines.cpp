#include "tools/datasets/dataset_lines.hpp"

#include <zlib.h>

#include <stdexcept>

namespace slamer {

DatasetLineReader::DatasetLineReader(const std::string& path) {
  gzFile file = gzopen(path.c_str(), "rb");  // reads plain files too
  if (file == nullptr) {
    throw std::runtime_error("cannot open dataset " + path);
  }
  file_ = file;
}

DatasetLineReader::~DatasetLineReader() {
  gzclose(static_cast<gzFile>(file_));
}

bool DatasetLineReader::next(std::string* line) {
  line->clear();
  char buffer[65536];
  bool got = false;
  while (gzgets(static_cast<gzFile>(file_), buffer, sizeof(buffer)) != nullptr) {
    got = true;
    *line += buffer;
    if (!line->empty() && line->back() == '\n') {
      line->pop_back();
      break;
    }
  }
  if (got) {
    ++line_number_;
  }
  return got;
}

}  // namespace slamer

// Reads a dataset file (plain or gzip) line by line, counting line numbers.
#pragma once

#include <cstdint>
#include <string>

namespace slamer {

class DatasetLineReader {
 public:
  // Throws std::runtime_error ("cannot open dataset PATH") if it cannot be opened.
  explicit DatasetLineReader(const std::string& path);
  ~DatasetLineReader();
  DatasetLineReader(const DatasetLineReader&) = delete;
  DatasetLineReader& operator=(const DatasetLineReader&) = delete;

  // The next line without its newline; false at the end of the file.
  bool next(std::string* line);
  int64_t line_number() const { return line_number_; }  // of the line last returned, from 1

 private:
  void* file_ = nullptr;  // gzFile
  int64_t line_number_ = 0;
};

}  // namespace slamer

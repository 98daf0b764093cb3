// libFuzzer target: the whole-file dataset importer (every format, corrected
// CARMEN detection on and off) on arbitrary bytes. First byte: format and
// mode; the rest is the file. Every stream must come out strictly increasing
// in utime, with one reference pose per scan or none.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <string>

#include "tools/datasets/dataset_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 1 || size > 200000) {
    return 0;
  }
  const int fd = memfd_create("dataset", 0);
  if (fd < 0) {
    return 0;
  }
  if (write(fd, data + 1, size - 1) != static_cast<ssize_t>(size - 1)) {
    close(fd);
    return 0;
  }
  slamer::ImportOptions options;
  options.format = static_cast<slamer::DatasetFormat>(data[0] % 3);
  options.corrected = static_cast<slamer::ImportOptions::Corrected>((data[0] / 3) % 3);
  const slamer::ImportedLog log = slamer::import_dataset("/proc/self/fd/" + std::to_string(fd), options);
  close(fd);
  for (std::size_t i = 1; i < log.scans.size(); ++i) {
    if (log.scans[i].utime <= log.scans[i - 1].utime) {
      __builtin_trap();
    }
  }
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    if (log.odometry[i].utime <= log.odometry[i - 1].utime) {
      __builtin_trap();
    }
  }
  if (!log.reference.empty() && log.reference.size() != log.scans.size()) {
    __builtin_trap();
  }
  const auto merged = slamer::merge_streams(log);
  for (std::size_t i = 1; i < merged.size(); ++i) {
    if (merged[i].utime < merged[i - 1].utime) {
      __builtin_trap();
    }
  }
  return 0;
}

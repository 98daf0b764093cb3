// libFuzzer target: the CMU wean.dat map reader on arbitrary bytes. It either
// returns a grid whose cells match its size or throws one runtime_error.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "tools/datasets/wean_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size > 200000) {
    return 0;
  }
  const int fd = memfd_create("wean", 0);
  if (fd < 0) {
    return 0;
  }
  if (write(fd, data, size) != static_cast<ssize_t>(size)) {
    close(fd);
    return 0;
  }
  try {
    const slamer::GridCells map = slamer::read_wean_map("/proc/self/fd/" + std::to_string(fd));
    if (map.cells.size() != map.geometry.size() || map.geometry.width <= 0 || map.geometry.height <= 0) {
      __builtin_trap();
    }
  } catch (const std::runtime_error&) {
  }
  close(fd);
  return 0;
}

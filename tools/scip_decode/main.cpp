// slamer-scip-decode FILE|-: a raw sensor->host SCIP byte stream, one JSON line per reply.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>

#include "drivers/urg/scip_reply.hpp"
#include "tools/scip_decode/scip_json.hpp"

int main(int argc, char** argv) {
  if (argc != 2 || std::strcmp(argv[1], "--help") == 0) {
    std::fprintf(stderr,
                 "usage: slamer-scip-decode FILE|-\n"
                 "  prints each SCIP reply of a raw sensor->host byte stream as one JSON line\n");
    return argc == 2 ? 0 : 2;
  }
  std::ifstream file;
  std::istream* in = &std::cin;
  if (std::strcmp(argv[1], "-") != 0) {
    file.open(argv[1], std::ios::binary);
    if (!file) {
      std::fprintf(stderr, "slamer-scip-decode: cannot open %s: %s\n", argv[1], std::strerror(errno));
      return 1;
    }
    in = &file;
  }
  slamer::urg::ReplyFramer framer;
  std::vector<std::string> lines;
  char buffer[4096];
  while (*in) {
    in->read(buffer, sizeof buffer);
    framer.feed(std::string_view(buffer, static_cast<std::size_t>(in->gcount())));
    while (framer.next(&lines)) {
      const auto reply = slamer::urg::parse_reply(lines);
      if (!reply.empty) {
        std::cout << slamer::urg::reply_to_json(reply) << '\n';
      }
    }
  }
  if (framer.buffered() > 0) {
    std::fprintf(stderr, "slamer-scip-decode: %zu bytes at the end without their blank line\n", framer.buffered());
  }
  return 0;
}

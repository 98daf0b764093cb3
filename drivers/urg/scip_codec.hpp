// SCIP 2.0 character codec and command encoding (SCIP 2.0 spec p6-9; see
// ../shared/protocols/scip.md "Framing and checksum", "Character encodings").
// Pure functions: no I/O.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace slamer::urg {

// (sum of the bytes) & 0x3F, + 0x30. "Hokuyo" -> 'o'.
char scip_checksum(std::string_view bytes);

// Checks a line whose last char is its checksum. Accepts the sum over every
// byte before it (inclusive form), over the bytes before a trailing ';'
// (the form real devices use on KEY:value; lines), and the UTM-30LX quirk of
// lines containing "<-" summed only up to the "<-".
bool line_checksum_ok(std::string_view line_with_sum);

// N-character encoding: 6 bits per char + 0x30, most significant first.
// decode takes 1..10 chars (60 bits); nullopt on more, none, or a char outside 0x30..0x6F.
std::string scip_encode(uint64_t value, int chars);
std::optional<uint64_t> scip_decode(std::string_view chars);

// Command line builders; `tag` (<= 16 chars, no ';' or LF) is appended as ";tag".
std::string scip_command(std::string_view command, std::string_view tag = {});
// MD (intensity=false) or ME: start(4) end(4) cluster(2) skip(1) scans(2; 0 = forever).
std::string scip_scan_command(bool intensity, int start, int end, int cluster, int skip, int scans,
                              std::string_view tag = {});

}  // namespace slamer::urg

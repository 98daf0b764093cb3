// SCIP 2.0 scan replies and sensor geometry (SCIP 2.0 spec p11-12; scip.md
// "MD/ME/GD layout"): MD/ME/GD/GE echo parameters, the 4-char timestamp, the
// 3-char distances (+ 3-char intensities for ME) that may straddle the 64-char
// data lines; geometry from the PP reply; device values to REP 117 ranges.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "drivers/urg/scip_reply.hpp"

namespace slamer::urg {

// PP values plus the model (VV/PP MODL) that decides the error-code table.
struct SensorGeometry {
  std::string model;
  int dmin = 0, dmax = 0;  // [mm]
  int ares = 0;            // steps per revolution
  int amin = 0, amax = 0, afrt = 0;
  int scan_rpm = 0;

  double angle_of_step(int step) const;  // (step - AFRT) * 2 pi / ARES
  double angle_increment() const;        // 2 pi / ARES
  double scan_period() const;            // 60 / SCAN [s]
  double time_increment() const;         // scan_period / ARES [s]
};
// From a PP reply; false with `error` naming the missing/bad key.
bool parse_geometry(const KeyValues& pp, SensorGeometry* geometry, std::string* error);

// What went wrong with a scan reply (kOk: usable).
enum class ScanError { kOk, kChecksum, kTruncated, kLength, kBadEcho, kBadChar, kStatus };
const char* scan_error_name(ScanError error);

struct ScanParams {
  bool intensity = false;   // ME/GE
  bool continuous = false;  // MD/ME (has skip + scans fields)
  int start = 0, end = 0, cluster = 1, skip = 0, scans = 0;
  int expected_values() const;  // ceil((end - start + 1) / max(cluster, 1))
};
// Parses the echo of an MD/ME/GD/GE command (with or without ";tag").
std::optional<ScanParams> parse_scan_echo(const std::string& echo);

struct ScanData {
  ScanParams params;
  uint32_t timestamp_ms = 0;  // 24-bit device clock
  std::vector<uint32_t> distances;
  std::vector<uint32_t> intensities;  // empty unless ME/GE
};
// Decodes one scan reply (status 99 for MD/ME, 00 for GD/GE). Values may
// straddle line breaks. Checks checksums, the line lengths and the count.
ScanError decode_scan(const Reply& reply, ScanData* scan);

// REP 117 (ros.org/reps/rep-0117.html: -Inf "too close to determine the true
// distance", +Inf "no information within the useful range, likely no object
// in range", NaN "an erroneous measurement with no useful physical
// quantification"). Values >= DMIN are metres; smaller ones are the error
// codes of SCIP 2.0 C-42-03320B p12 (also decoded this way by ROS's
// hokuyo_node, the REP author's driver):
// - table 3 (URG-04LX, UBG-04LX-F01, UHG-08LX; codes 0-19): 0 "detected
//   object is possibly at 22 m" (beyond the range) -> +inf; 1-2 "reflected
//   light has low intensity", 6-19 (errors of neighbouring steps, of the last
//   scans, strong reflectors, non-measurable steps, others) and the unlisted
//   3-5 -> NaN. (Older editions call 6 "possibly at 5.7 m"; the spec revision
//   here says "others".)
// - table 4 (UTM-30LX, used for every other model): 1 "no object in the range"
//   -> +inf; 2 "object is too near" and 4 "object out of range (at the near
//   end)" -> -inf; 3 "measurement error (interference)", 5 "other errors" and
//   any other value below DMIN -> NaN.
float range_from_device(uint32_t value, const SensorGeometry& geometry);

}  // namespace slamer::urg

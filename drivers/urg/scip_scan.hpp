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

// REP 117: values >= DMIN are metres; smaller ones are error codes: per the
// model family (URG-04LX table 3: 0 "possibly beyond 22 m" and 1-5 "low
// intensity" = no echo -> +inf; UTM-30LX table 4: 1 "no object in range" ->
// +inf, 2 "too near" and 4 "out of range at the near end" -> -inf); every
// other code -> NaN.
float range_from_device(uint32_t value, const SensorGeometry& geometry);

}  // namespace slamer::urg

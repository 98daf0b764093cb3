// Scans from outside for slamer-urg-sim (issue 13 "The emulator": "live from
// an LCM channel" and "an LCM log"): a REP 117 scan (laser_scan_t's library
// form, e.g. slamer-sim's) turned into the device values the emulated model
// would send for its steps AMIN..AMAX. Pure: no I/O, no clock.
//
// Geometry: the scan must fit the model (nranges = AMAX - AMIN + 1, the angle
// increment 2 pi / ARES, angle_min at AMIN, the scan period 60 / SCAN);
// otherwise the conversion fails with a one-line reason (the emulator does not
// invent a geometry the driver would then read from PP).
// Values (SCIP 2.0 spec p12 tables 3 and 4, the codes drivers/urg maps back):
// finite ranges in whole mm (rounded); below DMIN -> "too near"; above DMAX or
// +inf -> "no object in range"; -inf -> "too near"; NaN -> a measurement error.
// URG-04LX-family models (table 3) have no "too near" code: -inf and ranges
// below DMIN become an error code too (NaN on the driver's side).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sensors/laser_scan.hpp"
#include "tools/urg_sim/sim_sensor.hpp"

namespace slamer::urg {

// The device values the model uses for the REP 117 classes.
struct SimErrorCodes {
  uint32_t no_echo = 1;   // +inf
  uint32_t too_near = 2;  // -inf
  uint32_t error = 3;     // NaN
};
SimErrorCodes sim_error_codes(const SimModel& model);

// False with `error` (one line; may be null) if `scan` does not fit `model`.
bool sim_scan_from(const LaserScan& scan, const SimModel& model, int64_t received_us, SimScan* out, std::string* error);

}  // namespace slamer::urg

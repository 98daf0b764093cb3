#include "tools/urg_sim/sim_scan_source.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace slamer::urg {

SimErrorCodes sim_error_codes(const SimModel& model) {
  SimErrorCodes codes;
  if (model.name.find("URG-04") != std::string::npos) {
    codes.no_echo = 0;    // table 3: "detected object is possibly at 22 m" (past the range)
    codes.too_near = 19;  // table 3 has no "too near": "non-measurable step"
    codes.error = 19;
  }
  return codes;
}

bool sim_scan_from(const LaserScan& scan, const SimModel& model, int64_t received_us, SimScan* out,
                   std::string* error) {
  const std::size_t beams = static_cast<std::size_t>(model.amax - model.amin + 1);
  const double increment = 2.0 * std::numbers::pi / model.ares;
  const double angle_min = (model.amin - model.afrt) * increment;
  const double period = 60.0 / model.scan_rpm;
  char text[256];
  if (scan.ranges.size() != beams) {
    std::snprintf(text, sizeof text, "the scan has %zu beams, the %s model %zu (AMIN %d..AMAX %d)", scan.ranges.size(),
                  model.name.c_str(), beams, model.amin, model.amax);
  } else if (std::abs(scan.angle_increment - increment) > 1e-6 * increment) {
    std::snprintf(text, sizeof text, "the scan's angle increment %.9g rad is not the %s model's 2 pi / %d",
                  scan.angle_increment, model.name.c_str(), model.ares);
  } else if (std::abs(scan.angle_min - angle_min) > 0.5 * increment) {
    std::snprintf(text, sizeof text, "the scan's angle_min %.6f rad is not the %s model's %.6f", scan.angle_min,
                  model.name.c_str(), angle_min);
  } else if (std::abs(scan.scan_period - period) > 0.01 * period) {
    std::snprintf(text, sizeof text, "the scan period %.6f s is not the %s model's %.6f s",
                  static_cast<double>(scan.scan_period), model.name.c_str(), period);
  } else if (!scan.intensities.empty() && scan.intensities.size() != beams) {
    std::snprintf(text, sizeof text, "the scan has %zu intensities for %zu beams", scan.intensities.size(), beams);
  } else {
    text[0] = '\0';
  }
  if (text[0] != '\0') {
    if (error != nullptr) {
      *error = text;
    }
    return false;
  }
  const SimErrorCodes codes = sim_error_codes(model);
  out->first_beam_us = scan.utime;
  out->received_us = received_us;
  out->values.resize(beams);
  for (std::size_t i = 0; i < beams; ++i) {
    const float r = scan.ranges[i];
    uint32_t value;
    if (std::isnan(r)) {
      value = codes.error;
    } else if (std::isinf(r)) {
      value = r > 0 ? codes.no_echo : codes.too_near;
    } else {
      const double mm = std::round(static_cast<double>(r) * 1000.0);
      if (mm < model.dmin) {
        value = codes.too_near;
      } else if (mm > model.dmax) {
        value = codes.no_echo;
      } else {
        value = static_cast<uint32_t>(mm);
      }
    }
    out->values[i] = value;
  }
  out->intensities.clear();
  for (const float v : scan.intensities) {
    out->intensities.push_back(std::isfinite(v) && v > 0 ? static_cast<uint32_t>(std::min(v, 262143.0f)) : 0u);
  }
  return true;
}

}  // namespace slamer::urg

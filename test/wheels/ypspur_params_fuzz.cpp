// libFuzzer: arbitrary .param text (as from GETEMBEDDEDPARAM) through the reader and the formulas.
#include <cstddef>
#include <cstdint>
#include <string>

#include "drivers/wheels/ypspur_params.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    const auto params =
        slamer::tfrog::RobotParams::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
    (void)slamer::tfrog::kinematics_from(params);
    (void)slamer::tfrog::connect_parameters(params, 1000, 11, 300);
  } catch (const slamer::ConfigError&) {
  }
  return 0;
}

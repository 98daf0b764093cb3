// slamer-wheels: the i-Cart mini's wheels. T-frog TF-2MD3 over USB serial
// (--device) or encoders over SocketCAN (--can); ODOMETRY and WHEEL_ENCODERS
// per frame, PROCESS_STATUS at 1 Hz, CMD_VEL in (T-frog).
#include "common/process/process_main.hpp"
#include "drivers/wheels/backends.hpp"

namespace {

int run(const slamer::CommandLine& cli) {
  if (!cli.has("config")) {
    throw slamer::CommandLineError("--config FILE is required (config/wheels.yaml)");
  }
  auto config = slamer::load_config<slamer::WheelsConfig>(cli);
  if (cli.has("device") && cli.has("can")) {
    throw slamer::CommandLineError("give --device or --can, not both");
  }
  if (cli.has("device")) {
    config.backend = "tfrog";
    config.tfrog.device = cli.get("device");
  }
  if (cli.has("can")) {
    config.backend = "can";
    config.can.interface = cli.get("can");
  }
  const auto bus = slamer::open_bus(cli, "slamer-wheels", config.process);
  if (config.backend == "can") {
    slamer::start_can(*bus, config);
  } else {
    slamer::start_tfrog(*bus, config);
  }
  return bus->run();
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-wheels",
      "Wheel driver of the i-Cart mini: T-frog TF-2MD3 board (YP-Spur protocol) or SocketCAN encoders ->\n"
      "ODOMETRY, WHEEL_ENCODERS; CMD_VEL -> wheel velocities with a command timeout; reconnects after an unplug.",
      [](slamer::CommandLine& cli) {
        cli.add_option("device", "PATH", "T-frog serial port (overrides tfrog.device; selects the T-frog backend)");
        cli.add_option("can", "IFACE", "CAN interface or unix:PATH (overrides can.interface; selects CAN)");
      },
      run);
}

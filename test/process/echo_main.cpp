// slamer-test-echo: a process on the common skeleton, for the process tests.
// It subscribes to the stack's input channels with their real types and
// republishes every message it decodes on "<CHANNEL>_ECHO".
#include "common/process/lcm_bus.hpp"
#include "common/process/process_main.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/velocity_command_t.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace {

struct Config {
  slamer::ProcessOptions process;
};
void read_options(const slamer::ConfigReader& reader, Config* config) {
  read_options(reader.section("process"), &config->process);
}

template <class Msg>
void echo(slamer::Bus& process, const std::string& channel) {
  process.subscribe<Msg>(
      channel,
      [&process, channel](const Msg& msg, const slamer::ReceiveInfo&) { process.publish(channel + "_ECHO", msg); },
      true);
}

}  // namespace

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-test-echo", "Republishes LIDAR, ODOMETRY, ... on <CHANNEL>_ECHO (process tests).",
      [](slamer::CommandLine&) {},
      [](const slamer::CommandLine& cli) {
        const auto config = slamer::load_config<Config>(cli);
        slamer::LcmBus process("slamer-test-echo", cli.get("lcm-url"), config.process);
        echo<slamer::laser_scan_t>(process, "LIDAR");
        echo<slamer::odometry_t>(process, "ODOMETRY");
        echo<slamer::wheel_encoders_t>(process, "WHEEL_ENCODERS");
        echo<slamer::line_objects_t>(process, "LINE_OBJECTS");
        echo<slamer::initial_pose_t>(process, "INITIAL_POSE");
        echo<slamer::velocity_command_t>(process, "CMD_VEL");
        return process.run();
      });
}

// slamer-tfrog-sim: a T-frog TF-2MD3 board on a pty, reached through a symlink
// (the loop: board_runner.hpp). Prints one line per change on stdout:
// "<utime> servo S0 S1 wref W0 W1", and
// "<utime> unplugged|plugged|watchdog|path-start|path-done X Y THETA DISTANCE FRAMES".
#include "common/process/command_line.hpp"
#include "common/process/process_main.hpp"
#include "tools/tfrog_sim/board_runner.hpp"

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-tfrog-sim",
      "Emulates a T-frog TF-2MD3 motor board (i-Cart mini) on a pty linked at --link, speaking the\n"
      "YP-Spur text and binary protocol, with knobs for damaged frames, unplug/replug and error states.",
      [](slamer::CommandLine& cli) {
        cli.add_option("link", "PATH", "symlink to create for the board's serial port");
        cli.add_option("robot", "FILE", "YP-Spur .param file of the robot", "config/robots/icart-mini.param");
        cli.add_option("protocol", "YPP:C:A", "protocol version the board reports", "YPP:11:02");
        cli.add_option("path", "V,W,T;...", "wheels pushed along these (v, omega, seconds) segments");
        cli.add_option("source-channel", "CHANNEL",
                       "wheels turned as the wheel_encoders_t on CHANNEL say (e.g. slamer-sim's)");
        cli.add_option("path-delay", "S", "start the path S seconds after streaming starts", "0.5");
        cli.add_option("corrupt-every", "N", "damage every Nth odometry frame (0: never)", "0");
        cli.add_option("drop-every", "N", "drop every Nth odometry frame", "0");
        cli.add_option("wrong-length-every", "N", "send every Nth frame one word short", "0");
        cli.add_option("error-bits", "B", "error_state bits motor 0 reports", "0");
        cli.add_option("unplug-at", "S", "unplug the USB at S seconds (negative: never)", "-1");
        cli.add_option("replug-after", "S", "plug back in after S seconds", "1");
        cli.add_option("duration", "S", "exit after S seconds (0: run until killed)", "0");
      },
      slamer::tfrog::run_board);
}

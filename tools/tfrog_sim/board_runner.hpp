// slamer-tfrog-sim's I/O loop (board_runner.cpp): runs the emulated board on
// the pty at --link with the options main.cpp declares, until --duration ends.
#pragma once

#include "common/process/command_line.hpp"

namespace slamer::tfrog {

int run_board(const CommandLine& cli);  // throws CommandLineError for a missing --link

}  // namespace slamer::tfrog

// slamer-launch --check: a launch file and everything it names, without
// starting anything. Each program's config is loaded with the loader the
// program itself uses (the project's option structs), and the files its
// arguments name (the localizer's --map and --robot, the simulator's --world)
// are loaded as the program would load them; each program is run with --help
// to see that the options passed to it are ones it lists.
#pragma once

#include <string>
#include <vector>

#include "tools/launch/launch_file.hpp"

namespace slamer::launch {

// Where a program is: a bare name in `search_dirs` (in order), else a path
// relative to `base_dir`. "" if there is no executable file there.
std::string find_program(const std::string& program, const std::string& base_dir,
                         const std::vector<std::string>& search_dirs);

// The programs whose configs and arguments can be checked (their file names).
std::vector<std::string> checked_programs();

// Checks one program's config ("" = none) and the files named in its args
// (relative to `working_dir`). Returns the problem as one line ("" if none);
// `known` is set false when slamer-launch has no checker for the program.
std::string check_program(const std::string& program, const std::string& config, const std::vector<std::string>& args,
                          const std::string& working_dir, bool* known);

// Every problem of the launch file at `path` and of what it names, one line
// each naming the file and key; empty when all is well.
std::vector<std::string> check_launch_file(const std::string& path, const std::vector<std::string>& search_dirs);

}  // namespace slamer::launch

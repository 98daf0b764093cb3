// What a program says to --help, for slamer-launch --check to see whether the
// options a launch file passes exist: run with stdin from /dev/null, stdout
// and stderr captured (at most 1 MB), killed after a timeout.
#pragma once

#include <string>
#include <vector>

namespace slamer::launch {

// The output of `program --help` ("" if it cannot be run or says nothing in time).
std::string program_help(const std::string& program_path, double timeout_s = 5.0);

// The options (`--name` or `--name=VALUE`) in `args` that `help` does not list
// as `--name`. Empty when `help` lists no option at all (nothing to compare).
std::vector<std::string> unlisted_options(const std::vector<std::string>& args, const std::string& help);

}  // namespace slamer::launch

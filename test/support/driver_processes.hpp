// Starting the drivers and their device emulators for process-level tests:
// slamer-urg-sim (TCP on a free loopback port) + slamer-urg, slamer-tfrog-sim
// (a pty behind a symlink) + slamer-wheels. Shared by the drivers' own tests
// and the simulated robot's end-to-end test.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "test/support/child_process.hpp"

namespace slamer::test {

// A path in the temp dir, unique to this test process.
std::string temp_path(const std::string& name);
// A loopback TCP port nobody listens on right now.
int free_port();

// slamer-urg-sim with `args`; waits until it listens and sets *port (0: a free one).
std::unique_ptr<ChildProcess> start_urg_sim(std::vector<std::string> args, int* port);
// slamer-urg with `config` (relative to the checkout) against 127.0.0.1:port on `url`.
std::unique_ptr<ChildProcess> start_urg(const std::string& url, int port, const std::vector<std::string>& extra = {},
                                        const std::string& config = "config/urg.yaml");

// slamer-tfrog-sim with the i-Cart mini's .param and `args`; waits for the pty symlink `link`.
std::unique_ptr<ChildProcess> start_tfrog_sim(const std::string& link, const std::vector<std::string>& args);
// slamer-wheels with `config` (relative to the checkout) on the board at `link`.
std::unique_ptr<ChildProcess> start_wheels(const std::string& url, const std::string& link,
                                           const std::string& config = "config/wheels.yaml");

}  // namespace slamer::test

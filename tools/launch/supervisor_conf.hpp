// The supervisord configuration slamer-launch generates from a launch file
// (supervisor 4: http://supervisord.org/configuration.html): supervisord in
// the foreground with a unix control socket in the run directory, and one
// [program:NAME] per enabled process that supervisor does not start by itself
// (slamer-launch starts the groups in order), restarts when respawn is set
// (autorestart, startsecs, startretries: a start that fails is retried after
// 1 s, 2 s, 3 s, ...), stops with SIGTERM then SIGKILL after stop_timeout, and
// logs stdout and stderr to LOG_DIR/NAME.log.
#pragma once

#include <string>
#include <vector>

#include "tools/launch/launch_file.hpp"

namespace slamer::launch {

// The control socket's path in the run directory.
std::string socket_path(const Directories& dirs);

// The command line of a process: its program, --config FILE, --lcm-url=URL
// (when lcm is set and the URL is not empty), then its args with ${log_dir}
// and ${run_dir} expanded.
std::vector<std::string> process_argv(const LaunchProcess& process, const std::string& program_path,
                                      const std::string& lcm_url, const Directories& dirs);

// One argument as supervisor's command= reads it back (shlex, then Python
// %-expansion): single-quoted, with '%' doubled.
std::string quote_argument(const std::string& arg);

// The whole supervisord.conf; `argvs[i]` is the command line of the i-th
// enabled process of `file`.
std::string supervisor_config(const LaunchFile& file, const std::vector<std::vector<std::string>>& argvs,
                              const Directories& dirs);

}  // namespace slamer::launch

// The launch file of slamer-launch (config/launch/*.yaml): the processes that
// make up a robot, run under Debian's supervisor. Format (every key optional
// unless marked; unknown keys are errors):
//
//   lcm_url: "udpm://239.255.76.67:7667?ttl=0"  # passed to every process as --lcm-url=URL
//                                               # ("" = LCM's default; slamer-launch --lcm-url overrides)
//   log_dir: slamer_logs      # NAME.log per process (stdout+stderr) and supervisord.log; relative to the
//                             # working directory slamer-launch starts in (--log-dir overrides)
//   run_dir: ""               # supervisord.conf and its control socket ("" = a fresh /tmp dir, removed
//                             # at exit; --run-dir overrides)
//   state_dir: slamer_state   # kept across runs, e.g. the localizer's pose file; relative like log_dir; made
//                             # only when an arg names ${state_dir} (--state-dir overrides;
//                             # the systemd unit passes /var/lib/slamer)
//   processes:                # at least one enabled
//     - name: localizer       # required; [A-Za-z0-9_-], unique; supervisor's program name
//       program: slamer-localizer  # required; a bare name is looked up beside slamer-launch, then in
//                             # PATH; a path is relative to this file
//       config: ../localizer.yaml  # passed as --config FILE, relative to this file; checked by --check
//                             # with the program's own loader
//       args: [--map, ../maps/small_room/map.yaml]  # more arguments; ${log_dir}, ${run_dir} and
//                             # ${state_dir} expand (to absolute paths).
//                             # Every process runs in this file's directory, so relative paths in
//                             # args are relative to this file too
//       group: 1              # start order: group 0 first, each group RUNNING before the next
//                             # starts; stopped in reverse (drivers and the logger 0, algorithms 1)
//       enabled: true         # false: listed but not started (slamer-launch --enable NAME)
//       respawn: true         # restarted by supervisor when it ends (autorestart)
//       required: false       # when it ends for good (exits without respawn, or FATAL after its
//                             # start retries) the whole launch stops: exit 0 if it exited with 0
//       lcm: true             # pass --lcm-url=URL (false for programs not on LCM)
//       start_seconds: 2      # up this long = started (supervisor startsecs); an earlier exit is a
//                             # failed start, retried with backoff (1 s, 2 s, ...)
//       start_retries: 5      # failed starts before FATAL (startretries)
//       stop_timeout: 10      # [s] after SIGTERM before SIGKILL (stopwaitsecs)
#pragma once

#include <map>
#include <string>
#include <vector>

namespace slamer::launch {

struct LaunchProcess {
  std::string name;
  std::string program;
  std::string config;  // resolved against the launch file; "" = no --config
  std::vector<std::string> args;
  int group = 0;
  bool enabled = true;
  bool respawn = true;
  bool required = false;
  bool lcm = true;
  int start_seconds = 2;
  int start_retries = 5;
  int stop_timeout = 10;
  // "FILE:LINE: key 'processes[i].KEY'" of its name, program, config and args, for messages.
  std::map<std::string, std::string> where;
};

struct LaunchFile {
  std::string source;     // the file as given
  std::string directory;  // its directory ("." if none): the processes' working directory
  std::string lcm_url;
  std::string log_dir = "slamer_logs";
  std::string run_dir;
  std::string state_dir = "slamer_state";
  std::vector<LaunchProcess> processes;
};

// The directories of a run, all absolute.
struct Directories {
  std::string launch_dir;  // the launch file's: where the processes run
  std::string log_dir;
  std::string run_dir;
  std::string state_dir;
};

// Reads a launch file. Every problem found (YAML syntax, unknown keys, missing
// or bad values, duplicate names) is appended to `problems` as one line
// "FILE:LINE: key 'K': problem"; what could be read is returned.
LaunchFile read_launch_file(const std::string& path, std::vector<std::string>* problems);
LaunchFile parse_launch_file(const std::string& yaml_text, const std::string& source_name,
                             std::vector<std::string>* problems);

// The value of `--flag VALUE` or `--flag=VALUE` in `args` ("" if absent).
std::string flag_value(const std::vector<std::string>& args, const std::string& flag);
bool has_flag(const std::vector<std::string>& args, const std::string& flag);

// `text` with ${log_dir}, ${run_dir} and ${state_dir} replaced; throws
// std::invalid_argument naming any other ${...}.
std::string expand(const std::string& text, const Directories& dirs);

}  // namespace slamer::launch

// slamer-launch's run: check the launch file, generate supervisord.conf, run
// supervisord as a child, start the groups in order (LaunchSequence), show the
// live status table from PROCESS_STATUS (tools/status) and supervisor's
// states, and on SIGINT/SIGTERM (or a required process ending) stop the
// groups in reverse, shut supervisord down and return the exit code.
#pragma once

#include <string>
#include <vector>

namespace slamer::launch {

struct LaunchRequest {
  std::string file;
  bool lcm_url_given = false;
  std::string lcm_url;
  std::string log_dir;    // "" = the file's
  std::string run_dir;    // "" = the file's
  std::string state_dir;  // "" = the file's
  std::vector<std::string> enable;
  std::vector<std::string> disable;
  std::vector<std::string> search_dirs;  // where bare program names are looked up
};

// Throws std::runtime_error with a one-line reason when it cannot start.
int run_launch(const LaunchRequest& request);

}  // namespace slamer::launch

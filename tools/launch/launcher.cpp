#include "tools/launch/launcher.hpp"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <thread>

#include "common/process/lcm_bus.hpp"
#include "common/process/log.hpp"
#include "slamer/process_status_t.hpp"
#include "tools/launch/launch_check.hpp"
#include "tools/launch/launch_sequence.hpp"
#include "tools/launch/supervisor_client.hpp"
#include "tools/launch/supervisor_conf.hpp"
#include "tools/status/status_table.hpp"

namespace slamer::launch {
namespace {

namespace fs = std::filesystem;
const char* const kName = "slamer-launch";

void info(const std::string& text) {
  log_line(kName, LogLevel::kInfo, text);
}
void warn(const std::string& text) {
  log_line(kName, LogLevel::kWarning, text);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", s);
  return text;
}

void set_enabled(LaunchFile* file, const std::vector<std::string>& names, bool enabled) {
  for (const std::string& name : names) {
    bool found = false;
    for (LaunchProcess& p : file->processes) {
      if (p.name == name) {
        p.enabled = enabled;
        found = true;
      }
    }
    if (!found) {
      throw std::runtime_error(file->source + " has no process '" + name + "' to " + (enabled ? "enable" : "disable"));
    }
  }
}

// Supervisor's states below PROCESS_STATUS's table.
std::string render_states(const std::vector<ProcessInfo>& infos) {
  std::string out = "\nSUPERVISOR\n";
  char line[400];
  for (const ProcessInfo& p : infos) {
    std::snprintf(line, sizeof line, "%-22s %-9s %s\n", p.name.c_str(), p.state.c_str(), p.description.c_str());
    out += line;
  }
  return out;
}

class Launcher {
 public:
  Launcher(LaunchFile file, Directories dirs, bool owns_run_dir)
      : file_(std::move(file)), dirs_(std::move(dirs)), owns_run_dir_(owns_run_dir), client_(socket_path(dirs_)) {}

  ~Launcher() {
    if (owns_run_dir_) {
      std::error_code ignored;
      fs::remove_all(dirs_.run_dir, ignored);
    }
  }

  int run(const std::vector<std::vector<std::string>>& argvs) {
    if (client_.reachable()) {
      throw std::runtime_error("a supervisord already answers on " + socket_path(dirs_) +
                               " (another slamer-launch with this run directory?)");
    }
    const std::string conf = dirs_.run_dir + "/supervisord.conf";
    std::ofstream(conf) << supervisor_config(file_, argvs, dirs_);
    std::vector<SequenceProcess> sequenced;
    for (const LaunchProcess& p : file_.processes) {
      if (p.enabled) {
        sequenced.push_back({p.name, p.group, p.required, p.respawn});
      }
    }
    LaunchSequence sequence(std::move(sequenced));
    // The bus first: it blocks SIGINT/SIGTERM (read from its signalfd) before supervisord is forked.
    LcmBus bus(kName, file_.lcm_url, ProcessOptions{});
    StatusTable table(StatusMonitorOptions{}.stale_after);
    bus.subscribe<process_status_t>(
        "PROCESS_STATUS", [&](const process_status_t& s, const ReceiveInfo& r) { table.update(s, r.receive_utime); });
    const auto start = std::chrono::steady_clock::now();
    Supervisord supervisord(conf);
    info("supervisord " + std::to_string(supervisord.pid()) + " on " + conf + "; logs in " + dirs_.log_dir);
    while (!client_.reachable()) {
      if (!supervisord.running()) {
        throw std::runtime_error("supervisord exited at start (see " + dirs_.log_dir + "/supervisord.log)");
      }
      if (seconds_since(start) > 15.0) {
        throw std::runtime_error("supervisord did not open " + socket_path(dirs_) + " within 15 s");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const bool terminal = isatty(STDOUT_FILENO) != 0;
    bool announced_up = false;
    int failures = 0;
    bus.every(0.2, [&] {
      if (!supervisord.running()) {
        log_line(kName, LogLevel::kError, "supervisord exited: stopping");
        supervisor_lost_ = true;
        bus.stop();
        return;
      }
      if (!poll(&sequence, &failures)) {
        bus.stop();
        return;
      }
      if (sequence.started() && !announced_up) {
        announced_up = true;
        info("all " + std::to_string(infos_.size()) + " processes up in " + format_seconds(seconds_since(start)));
      }
      update_state(bus);
      if (sequence.stopping()) {
        bus.stop();
      }
    });
    if (terminal) {
      bus.every(1.0, [&] {
        std::cout << "\033[H\033[2J" << table.render_text(now_utime()) << render_states(infos_) << std::flush;
      });
    }
    bus.run();
    const auto stop_start = std::chrono::steady_clock::now();
    sequence.request_stop("stop");
    if (!supervisor_lost_) {
      stop_all(&sequence);
      try {
        client_.call("supervisor.shutdown");
      } catch (const std::exception& e) {
        warn(std::string("supervisor.shutdown: ") + e.what());
      }
      if (!supervisord.wait(15.0)) {
        warn("supervisord did not exit within 15 s: killing it");
        supervisord.kill_now();
      }
    } else {
      // supervisord is gone: its children would be left running.
      for (const ProcessInfo& p : infos_) {
        if (p.pid > 0) {
          warn("supervisord is gone: SIGTERM to " + p.name + " (pid " + std::to_string(p.pid) + ")");
          ::kill(static_cast<pid_t>(p.pid), SIGTERM);
        }
      }
    }
    info("stopped in " + format_seconds(seconds_since(stop_start)) + ", exit " +
         std::to_string(supervisor_lost_ ? 1 : sequence.exit_code()));
    return supervisor_lost_ ? 1 : sequence.exit_code();
  }

 private:
  // One round: supervisor's states into the sequence, its starts and stops out.
  // False after 10 failed calls in a row (about 2 s without supervisord).
  bool poll(LaunchSequence* sequence, int* failures) {
    try {
      infos_ = client_.processes();
      *failures = 0;
    } catch (const std::exception& e) {
      if (++*failures >= 10) {
        log_line(kName, LogLevel::kError, std::string("supervisord does not answer: ") + e.what());
        supervisor_lost_ = true;
        return false;
      }
      return true;
    }
    const SequenceActions actions = sequence->update(infos_);
    for (const std::string& line : actions.messages) {
      info(line);
    }
    for (const std::string& name : actions.start) {
      const std::string fault = client_.start(name);
      if (!fault.empty()) {
        warn("starting " + name + ": " + fault);
      }
    }
    for (const std::string& name : actions.stop) {
      if (stopping_.insert(name).second) {
        info("stopping " + name);
      }
      client_.stop(name);  // faults: it ended meanwhile; the next round sees that
    }
    return true;
  }

  // Stops group by group; supervisor's stopwaitsecs bound each (SIGKILL after).
  void stop_all(LaunchSequence* sequence) {
    int longest = 1;
    for (const LaunchProcess& p : file_.processes) {
      longest += p.stop_timeout + 2;
    }
    const auto start = std::chrono::steady_clock::now();
    int failures = 0;
    while (!sequence->done() && seconds_since(start) < longest) {
      if (!poll(sequence, &failures)) {
        return;
      }
      if (!sequence->done()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    }
  }

  // slamer-launch's own PROCESS_STATUS: degraded while a process is not running.
  void update_state(LcmBus& bus) {
    std::string down;
    for (const ProcessInfo& p : infos_) {
      if (p.state == "FATAL" || p.state == "BACKOFF" || p.state == "EXITED") {
        down += (down.empty() ? "" : ", ") + p.name + " " + p.state;
      }
    }
    bus.set_state(down.empty() ? process_status_t::OK : process_status_t::DEGRADED, down);
  }

  LaunchFile file_;
  Directories dirs_;
  bool owns_run_dir_;
  SupervisorClient client_;
  std::vector<ProcessInfo> infos_;
  std::set<std::string> stopping_;
  bool supervisor_lost_ = false;
};

}  // namespace

int run_launch(const LaunchRequest& request) {
  const std::vector<std::string> problems = check_launch_file(request.file, request.search_dirs);
  for (const std::string& problem : problems) {
    std::cerr << problem << "\n";
  }
  if (!problems.empty()) {
    throw std::runtime_error(request.file + ": " + std::to_string(problems.size()) +
                             " problem(s), nothing started (slamer-launch --check lists them)");
  }
  std::vector<std::string> ignored;
  LaunchFile file = read_launch_file(request.file, &ignored);
  set_enabled(&file, request.enable, true);
  set_enabled(&file, request.disable, false);
  if (request.lcm_url_given) {
    file.lcm_url = request.lcm_url;
  }
  Directories dirs;
  dirs.launch_dir = fs::absolute(file.directory).lexically_normal().string();
  dirs.log_dir = fs::absolute(request.log_dir.empty() ? file.log_dir : request.log_dir).lexically_normal().string();
  fs::create_directories(dirs.log_dir);
  dirs.state_dir =
      fs::absolute(request.state_dir.empty() ? file.state_dir : request.state_dir).lexically_normal().string();
  for (const LaunchProcess& p : file.processes) {
    for (const std::string& arg : p.args) {
      if (p.enabled && arg.find("${state_dir}") != std::string::npos) {
        fs::create_directories(dirs.state_dir);  // only when something keeps its state there
      }
    }
  }
  const std::string run_dir = request.run_dir.empty() ? file.run_dir : request.run_dir;
  bool owns_run_dir = false;
  if (run_dir.empty()) {
    char pattern[] = "/tmp/slamer-launch-XXXXXX";
    if (mkdtemp(pattern) == nullptr) {
      throw std::runtime_error("cannot create a run directory in /tmp");
    }
    dirs.run_dir = pattern;
    owns_run_dir = true;
  } else {
    dirs.run_dir = fs::absolute(run_dir).lexically_normal().string();
    fs::create_directories(dirs.run_dir);
  }
  if (socket_path(dirs).size() > 100) {
    throw std::runtime_error("run directory path too long for a unix socket: " + dirs.run_dir);
  }
  std::vector<std::vector<std::string>> argvs;
  for (const LaunchProcess& p : file.processes) {
    if (p.enabled) {
      argvs.push_back(
          process_argv(p, find_program(p.program, file.directory, request.search_dirs), file.lcm_url, dirs));
    }
  }
  Launcher launcher(std::move(file), dirs, owns_run_dir);
  return launcher.run(argvs);
}

}  // namespace slamer::launch

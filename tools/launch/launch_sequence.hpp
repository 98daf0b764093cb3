// The order in which slamer-launch starts and stops a launch file's processes,
// as a state machine fed with supervisor's process states (no I/O, no clock):
// groups start in increasing order, each once all of the previous group are
// RUNNING (or ended for good, if not required); stops go group by group in
// reverse, each group gone (STOPPED, EXITED, FATAL) before the next; a
// required process that ends for good (EXITED without respawn, or FATAL) stops
// the launch, with exit code 0 only if it exited with status 0.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "tools/launch/xmlrpc.hpp"

namespace slamer::launch {

struct SequenceProcess {
  std::string name;
  int group = 0;
  bool required = false;
  bool respawn = true;
};

struct SequenceActions {
  std::vector<std::string> start;     // supervisor.startProcess each
  std::vector<std::string> stop;      // supervisor.stopProcess each
  std::vector<std::string> messages;  // one line each: state changes, why the launch stops
};

class LaunchSequence {
 public:
  explicit LaunchSequence(std::vector<SequenceProcess> processes);

  // The latest states of every process (supervisor.getAllProcessInfo).
  SequenceActions update(const std::vector<ProcessInfo>& infos);
  // Ordered shutdown from where the start has got to (Ctrl-C, SIGTERM).
  void request_stop(const std::string& why);

  bool started() const { return phase_ == Phase::kRun; }  // every group up
  bool stopping() const { return phase_ == Phase::kStop || phase_ == Phase::kDone; }
  bool done() const { return phase_ == Phase::kDone; }
  int exit_code() const { return exit_code_; }
  const std::vector<int>& groups() const { return groups_; }

 private:
  enum class Phase { kStart, kRun, kStop, kDone };
  std::vector<const SequenceProcess*> in_group(int group) const;
  void check_required(const std::map<std::string, ProcessInfo>& by_name, SequenceActions* actions);

  std::vector<SequenceProcess> processes_;
  std::vector<int> groups_;  // distinct, increasing
  Phase phase_ = Phase::kStart;
  std::size_t group_index_ = 0;  // the group being started, then stopped
  bool issued_ = false;          // starts of the current group sent
  int exit_code_ = 0;
  std::map<std::string, std::string> last_state_;
};

}  // namespace slamer::launch

#include "tools/launch/launch_sequence.hpp"

#include <algorithm>
#include <set>

namespace slamer::launch {
namespace {

bool is_running(const std::string& state) {
  return state == "STARTING" || state == "RUNNING" || state == "BACKOFF";
}

bool ended_for_good(const SequenceProcess& p, const ProcessInfo& info) {
  return info.state == "FATAL" || (info.state == "EXITED" && !p.respawn);
}

}  // namespace

LaunchSequence::LaunchSequence(std::vector<SequenceProcess> processes) : processes_(std::move(processes)) {
  std::set<int> groups;
  for (const SequenceProcess& p : processes_) {
    groups.insert(p.group);
  }
  groups_.assign(groups.begin(), groups.end());
  if (groups_.empty()) {
    phase_ = Phase::kDone;
  }
}

std::vector<const SequenceProcess*> LaunchSequence::in_group(int group) const {
  std::vector<const SequenceProcess*> members;
  for (const SequenceProcess& p : processes_) {
    if (p.group == group) {
      members.push_back(&p);
    }
  }
  return members;
}

void LaunchSequence::request_stop(const std::string& why) {
  (void)why;
  if (phase_ == Phase::kStart || phase_ == Phase::kRun) {
    if (phase_ == Phase::kRun) {
      group_index_ = groups_.size() - 1;
    }
    phase_ = Phase::kStop;
  }
}

void LaunchSequence::check_required(const std::map<std::string, ProcessInfo>& by_name, SequenceActions* actions) {
  for (const SequenceProcess& p : processes_) {
    const auto it = by_name.find(p.name);
    if (!p.required || it == by_name.end() || !ended_for_good(p, it->second)) {
      continue;
    }
    const bool clean = it->second.state == "EXITED" && it->second.exit_status == 0;
    exit_code_ = clean ? exit_code_ : 1;
    actions->messages.push_back("required process '" + p.name + "' " +
                                (clean ? "finished" : "ended for good (" + it->second.state + ")") +
                                ": stopping the launch");
    request_stop(p.name);
    return;
  }
}

SequenceActions LaunchSequence::update(const std::vector<ProcessInfo>& infos) {
  SequenceActions actions;
  std::map<std::string, ProcessInfo> by_name;
  for (const ProcessInfo& info : infos) {
    by_name[info.name] = info;
    std::string& last = last_state_[info.name];
    if (last != info.state && !last.empty()) {
      std::string line = info.name + ": " + last + " -> " + info.state;
      if (info.pid != 0) {
        line += " (pid " + std::to_string(info.pid) + ")";
      }
      if (info.state == "EXITED" || info.state == "FATAL" || info.state == "BACKOFF") {
        line += ": " + info.description;
      }
      actions.messages.push_back(line);
    }
    last = info.state;
  }
  if (phase_ == Phase::kStart || phase_ == Phase::kRun) {
    check_required(by_name, &actions);
  }
  if (phase_ == Phase::kStart) {
    const int group = groups_[group_index_];
    const std::vector<const SequenceProcess*> members = in_group(group);
    if (!issued_) {
      for (const SequenceProcess* p : members) {
        actions.start.push_back(p->name);
      }
      actions.messages.push_back("starting group " + std::to_string(group));
      issued_ = true;
      return actions;
    }
    const bool settled = std::all_of(members.begin(), members.end(), [&](const SequenceProcess* p) {
      const auto it = by_name.find(p->name);
      return it != by_name.end() && (it->second.state == "RUNNING" || ended_for_good(*p, it->second));
    });
    if (settled) {
      issued_ = false;
      if (++group_index_ == groups_.size()) {
        group_index_ = groups_.size() - 1;
        phase_ = Phase::kRun;
        actions.messages.push_back("every group is up");
      }
    }
    return actions;
  }
  if (phase_ == Phase::kStop) {
    for (;;) {
      const int group = groups_[group_index_];
      bool gone = true;
      for (const SequenceProcess* p : in_group(group)) {
        const auto it = by_name.find(p->name);
        const std::string state = it == by_name.end() ? "STOPPED" : it->second.state;
        if (is_running(state)) {
          actions.stop.push_back(p->name);
        }
        // A respawning process that just EXITED is about to be started again.
        const bool settled = state == "STOPPED" || state == "FATAL" || (state == "EXITED" && !p->respawn);
        gone = gone && settled;
      }
      if (!gone) {
        return actions;
      }
      if (group_index_ == 0) {
        phase_ = Phase::kDone;
        return actions;
      }
      --group_index_;
      if (!actions.stop.empty()) {
        return actions;
      }
    }
  }
  return actions;
}

}  // namespace slamer::launch

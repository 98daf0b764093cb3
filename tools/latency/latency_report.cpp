#include "tools/latency/latency_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/stats/rolling_percentiles.hpp"

namespace slamer {
namespace {

LatencyStats stats_of(const std::vector<double>& ms) {
  LatencyStats s;
  s.count = static_cast<int64_t>(ms.size());
  if (ms.empty()) {
    return s;
  }
  RollingPercentiles all(ms.size());
  for (const double v : ms) {
    all.add(v);
  }
  s.p50_ms = all.percentile(0.5);
  s.p99_ms = all.percentile(0.99);
  s.max_ms = all.percentile(1.0);
  return s;
}

double ms_between(int64_t from_utime, int64_t to_utime) {
  return static_cast<double>(to_utime - from_utime) * 1e-3;
}

nlohmann::json to_json(const LatencyStats& s) {
  return {{"count", s.count}, {"p50_ms", s.p50_ms}, {"p99_ms", s.p99_ms}, {"max_ms", s.max_ms}};
}

}  // namespace

void LatencyRecorder::on_scan(int64_t utime, int64_t seq, double sweep_s, int64_t bus_utime) {
  if (by_utime_.count(utime) != 0) {
    return;  // a duplicate: the first one counts
  }
  if (last_seq_ && seq > *last_seq_ + 1) {
    seq_skipped_ += seq - *last_seq_ - 1;
  }
  if (!last_seq_ || seq > *last_seq_) {
    last_seq_ = seq;
  }
  by_utime_[utime] = scans_.size();
  scans_.push_back({utime, std::isfinite(sweep_s) && sweep_s > 0.0 ? sweep_s : 0.0, bus_utime, {}, {}});
}

void LatencyRecorder::on_objects(int64_t scan_utime, int64_t bus_utime) {
  const auto it = by_utime_.find(scan_utime);
  if (it == by_utime_.end()) {
    ++unmatched_objects_;
  } else if (!scans_[it->second].objects_bus) {
    scans_[it->second].objects_bus = bus_utime;
  }
}

void LatencyRecorder::on_pose(int64_t scan_utime, int64_t bus_utime) {
  const auto it = by_utime_.find(scan_utime);
  if (it == by_utime_.end()) {
    ++unmatched_poses_;
  } else if (!scans_[it->second].pose_bus) {
    scans_[it->second].pose_bus = bus_utime;
  }
}

void LatencyRecorder::on_status(const std::string& process, int32_t pid, const ProcessTotals& totals) {
  statuses_[process][pid] = totals;  // the counters are since that pid started: its last status has them all
}

LatencyReport LatencyRecorder::report() const {
  LatencyReport r;
  r.scans = static_cast<int64_t>(scans_.size());
  r.scans_lost_before_bus = seq_skipped_;
  r.unmatched_objects = unmatched_objects_;
  r.unmatched_poses = unmatched_poses_;
  std::vector<double> lidar, objects, pose, after_sweep;
  int64_t first = 0, last = 0;
  for (const Scan& s : scans_) {
    first = lidar.empty() ? s.utime : std::min(first, s.utime);
    last = lidar.empty() ? s.utime : std::max(last, s.utime);
    lidar.push_back(ms_between(s.utime, s.lidar_bus));
    if (s.objects_bus) {
      objects.push_back(ms_between(s.utime, *s.objects_bus));
    } else {
      ++r.scans_without_objects;
    }
    if (s.pose_bus) {
      pose.push_back(ms_between(s.utime, *s.pose_bus));
      after_sweep.push_back(pose.back() - s.sweep_s * 1e3);
    } else {
      ++r.scans_without_pose;
    }
  }
  r.duration_s = static_cast<double>(last - first) * 1e-6;
  r.lidar = stats_of(lidar);
  r.objects = stats_of(objects);
  r.pose = stats_of(pose);
  r.pose_after_last_beam = stats_of(after_sweep);
  for (const auto& [name, by_pid] : statuses_) {
    ProcessTotals sum;  // a restarted process has a new pid and counts from zero: add them up
    sum.process = name;
    sum.pids = static_cast<int>(by_pid.size());
    for (const auto& [pid, t] : by_pid) {
      sum.messages_in += t.messages_in;
      sum.messages_out += t.messages_out;
      sum.decode_errors += t.decode_errors;
      sum.drops += t.drops;
      sum.processing_p99_ms = std::max(sum.processing_p99_ms, t.processing_p99_ms);
    }
    r.processes.push_back(sum);
  }
  return r;
}

std::string render_text(const LatencyReport& r) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line),
                "%lld scans over %.1f s; lost before the bus %lld, without LINE_OBJECTS %lld, without POSE %lld\n",
                static_cast<long long>(r.scans), r.duration_s, static_cast<long long>(r.scans_lost_before_bus),
                static_cast<long long>(r.scans_without_objects), static_cast<long long>(r.scans_without_pose));
  out += line;
  out += "latency [ms]                     count      p50      p99      max\n";
  const auto row = [&](const char* name, const LatencyStats& s) {
    std::snprintf(line, sizeof(line), "%-30s %7lld %8.2f %8.2f %8.2f\n", name, static_cast<long long>(s.count),
                  s.p50_ms, s.p99_ms, s.max_ms);
    out += line;
  };
  row("first beam -> LIDAR", r.lidar);
  row("first beam -> LINE_OBJECTS", r.objects);
  row("first beam -> POSE", r.pose);
  row("last beam -> POSE", r.pose_after_last_beam);
  if (!r.processes.empty()) {
    out += "process (last PROCESS_STATUS)    runs       in      out  decode_err    drops  p99 [ms]\n";
    for (const ProcessTotals& p : r.processes) {
      std::snprintf(line, sizeof(line), "%-30s %6d %8lld %8lld %11lld %8lld %9.2f\n", p.process.c_str(), p.pids,
                    static_cast<long long>(p.messages_in), static_cast<long long>(p.messages_out),
                    static_cast<long long>(p.decode_errors), static_cast<long long>(p.drops), p.processing_p99_ms);
      out += line;
    }
  }
  return out;
}

std::string render_json(const LatencyReport& r) {
  nlohmann::json processes = nlohmann::json::array();
  for (const ProcessTotals& p : r.processes) {
    processes.push_back({{"process", p.process},
                         {"runs", p.pids},
                         {"messages_in", p.messages_in},
                         {"messages_out", p.messages_out},
                         {"decode_errors", p.decode_errors},
                         {"drops", p.drops},
                         {"processing_p99_ms", p.processing_p99_ms}});
  }
  const nlohmann::json j = {{"duration_s", r.duration_s},
                            {"scans", r.scans},
                            {"scans_lost_before_bus", r.scans_lost_before_bus},
                            {"scans_without_objects", r.scans_without_objects},
                            {"scans_without_pose", r.scans_without_pose},
                            {"unmatched_objects", r.unmatched_objects},
                            {"unmatched_poses", r.unmatched_poses},
                            {"lidar", to_json(r.lidar)},
                            {"objects", to_json(r.objects)},
                            {"pose", to_json(r.pose)},
                            {"pose_after_last_beam", to_json(r.pose_after_last_beam)},
                            {"processes", processes}};
  return j.dump(2) + "\n";
}

}  // namespace slamer

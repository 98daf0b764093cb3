// The one wiring of slamer-localizer, whatever the bus (bus.hpp): live on
// LCM, replaying a log, or in memory in a test.
//   LIDAR, ODOMETRY, LINE_OBJECTS, INITIAL_POSE in -> LocalizerNode;
//   after each processed scan: POSE, SEMANTIC_OBJECTS, PARTICLES (rate
//   limited) out, PROCESS_STATUS's state from the filter and the inputs;
//   a 10 ms timer releases scans whose objects did not come in time;
//   every input checked first (input_checks.hpp): what is refused is a drop
//   of its channel, with its reason in the log at most once a second; stale
//   input is a drop too (the node's counters, read when the status goes out);
//   with a pose file: resume from it at the start (UNCERTAIN, its sigma grown
//   by the downtime, until the scans confirm it: LocalizerNode::resume), save
//   it periodically and at the end.
#pragma once

#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "common/process/bus.hpp"
#include "common/robot/robot_options.hpp"
#include "localizer/input_checks.hpp"
#include "localizer/localizer_config.hpp"
#include "localizer/localizer_node.hpp"
#include "localizer/pose_keeper.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/odometry_t.hpp"

namespace slamer {

class LocalizerProcess {
 public:
  // `keep_pose`: use config.pose_file (live runs; a replay leaves the robot's file alone).
  LocalizerProcess(Bus& bus, const LocalizerProcessConfig& config, const RobotOptions& robot, LocalizerNode node,
                   bool keep_pose);
  // The bus holds callbacks that point at this object: it stays where it was made.
  LocalizerProcess(const LocalizerProcess&) = delete;
  LocalizerProcess& operator=(const LocalizerProcess&) = delete;

  const LocalizerNode& node() const { return node_; }
  int64_t scans_published() const { return scans_published_; }

 private:
  void on_scan(const laser_scan_t& message);
  void on_odometry(const odometry_t& message);
  void on_initial_pose(const initial_pose_t& message);
  void refuse(const std::string& channel, const std::string& reason);
  void publish_ready();
  void publish(const UpdateResult& result);
  void save_pose();

  Bus& bus_;
  LocalizerProcessConfig config_;
  LocalizerNode node_;
  PoseKeeper pose_keeper_;
  InputLimits limits_;
  StreamTime scan_time_;
  StreamTime odometry_time_;
  std::optional<std::pair<int64_t, Pose2>> last_odometry_;
  StreamRestart scan_restart_;
  StreamRestart odometry_restart_;
  std::optional<int64_t> last_initial_pose_;  // bus time
  RefusalCounter refused_;
  // Scans far from the stream's time, held until the next ones say whether
  // the stream moved there (a gap in a log, a sensor back after minutes) or
  // they were odd ones (then refused).
  std::vector<std::pair<LaserScan, int64_t>> held_scans_;
  std::vector<std::pair<int64_t, Pose2>> held_odometry_;  // the same for odometry
  int64_t last_particles_utime_;
  int64_t scans_published_ = 0;
  int64_t scans_lost_said_ = 0;  // scans lost on the way already warned about
  bool resume_reported_ = false;
};

}  // namespace slamer

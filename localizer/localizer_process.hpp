// The one wiring of slamer-localizer, whatever the bus (bus.hpp): live on
// LCM, replaying a log, or in memory in a test.
//   LIDAR, ODOMETRY, LINE_OBJECTS, INITIAL_POSE in -> LocalizerNode;
//   after each processed scan: POSE, SEMANTIC_OBJECTS, PARTICLES (rate
//   limited) out, PROCESS_STATUS's state from the filter and the inputs;
//   a 10 ms timer releases scans whose objects did not come in time;
//   refused and stale input counted as drops of its channel (the node's
//   counters, read when the status goes out);
//   with a pose file: resume from it at the start, save it periodically and
//   at the end.
#pragma once

#include <memory>

#include "common/process/bus.hpp"
#include "localizer/localizer_config.hpp"
#include "localizer/localizer_node.hpp"
#include "localizer/pose_keeper.hpp"

namespace slamer {

class LocalizerProcess {
 public:
  // `keep_pose`: use config.pose_file (live runs; a replay leaves the robot's file alone).
  LocalizerProcess(Bus& bus, const LocalizerProcessConfig& config, LocalizerNode node, bool keep_pose);

  const LocalizerNode& node() const { return node_; }
  int64_t scans_published() const { return scans_published_; }

 private:
  void publish_ready();
  void publish(const UpdateResult& result);
  void save_pose();

  Bus& bus_;
  LocalizerProcessConfig config_;
  LocalizerNode node_;
  PoseKeeper pose_keeper_;
  int64_t last_particles_utime_;
  int64_t scans_published_ = 0;
};

}  // namespace slamer

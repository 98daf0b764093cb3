// What a running localizer does around the filter:
//  * keeps odometry to interpolate it to each scan's time, holding a scan
//    up to `odometry_wait` for odometry past its time;
//  * pairs each scan with its recognized objects, holding scans (in order) up
//    to `objects_wait` for them; a scan is released without objects when a
//    later scan's objects came first, or the recognizer is missing; objects
//    that come after their scan went are counted apart from objects of a scan
//    that never reached us (lost on the way: not a wait cut short);
//  * holds objects that come before their scan (two senders, the driver and
//    the recognizer: nothing orders their datagrams at this receiver, and one
//    sandboxed network stack reordered 3 % of them) until the scan comes or a
//    later scan shows it never will;
//  * drops stale (duplicate, out-of-order) input and starts over when time
//    jumps backwards (a log replayed from the top), by one rule (StreamOrder);
//  * degrades when a stream is missing: without odometry the particles
//    diffuse at up to `no_odometry_speed`; without objects, geometry only.
// No clock and no LCM: times come with the inputs; `now` is passed in.
#pragma once

#include <deque>
#include <optional>

#include "common/process/stream_order.hpp"
#include "localizer/particle_filter.hpp"

namespace slamer {

struct NodeCounters {
  int64_t stale_scans = 0;  // not newer than the last scan
  int64_t stale_odometry = 0;
  int64_t stale_objects = 0;  // late (their scan went without them) or twice
  // For a scan that never reached us (UDP lost it here, not at the recognizer):
  // discarded too, but the loss is the scan's, not a wait cut short.
  int64_t objects_without_scan = 0;
  int64_t objects_before_scan = 0;  // came first, joined their scan when it came (not a drop)
  int64_t scans_without_objects = 0;
  int64_t scans_without_odometry = 0;
  int64_t resets = 0;            // time went backwards
  int64_t invalid_odometry = 0;  // non-finite pose
  int64_t invalid_initial_poses = 0;
};

// Which inputs the last processed scan had to do without.
struct InputHealth {
  bool odometry_missing = false;
  bool objects_missing = false;  // only when the mode uses objects
  double odometry_age = 0.0;     // [s] of the newest odometry at the last scan (inf: none yet)
  double objects_age = 0.0;      // [s] of the newest objects at the last scan (inf: none yet)
};

class LocalizerNode {
 public:
  LocalizerNode(const SemanticMap& map, const LocalizerOptions& options, const Pose2& lidar_mount);

  void on_odometry(int64_t utime, const Pose2& pose);
  // Returns false (and changes nothing) for a non-finite pose or sigma.
  bool on_initial_pose(const Pose2& pose, const std::vector<double>& sigma);
  // The odometry jumped (a driver restart, a glitch): the step is not
  // integrated; the next odometry is the new reference.
  void restart_odometry();
  // A pose read back after a restart (the pose file), from the scan at
  // `saved_utime`. The robot may have moved while the process was down: at
  // the first scan, resume.moved_fraction of the particles spread with a
  // sigma grown by resume.speed and resume.turn_rate times the downtime (that
  // scan's utime - saved_utime), the rest at the saved sigma (it stayed), and
  // the filter says UNCERTAIN until the scans confirm it (ParticleFilter::
  // require_confirmation); down longer than resume.max_downtime, or a saved
  // time after the scan's (clocks that disagree): global localization.
  // Returns false (and changes nothing) for a non-finite pose or sigma.
  bool resume(const Pose2& pose, const std::vector<double>& sigma, int64_t saved_utime);
  bool on_map(double x, double y) const { return filter_.geometry().cell_at({x, y}).has_value(); }
  // Global localization on demand (an INITIAL_POSE whose cov[0] is negative):
  // particles uniform over the map's free space, relocalized from the scans.
  void request_global_localization();
  // `arrival_utime`: when the process took the scan in, in the clock `now` of
  // poll() is given in. A scan waits for its objects measured from its
  // arrival, so a log played live (old utimes, new arrival times) waits as it did.
  void on_scan(const LaserScan& scan, int64_t arrival_utime);
  // A scan that arrives at its own utime (offline callers on the sensor's clock).
  void on_scan(const LaserScan& scan) { on_scan(scan, scan.utime); }
  void on_objects(const LineObjectSet& objects);
  // Processes the oldest waiting scan if it may go (see above) by `now_utime`
  // (the arrival times' clock); INT64_MAX flushes every waiting scan.
  // Call until it returns nothing.
  std::optional<UpdateResult> poll(int64_t now_utime);
  // What the last resume() found at its first scan (nullopt before).
  struct Resumed {
    double downtime = 0.0;  // [s]
    bool global = false;    // too long, or a clock that disagrees: global localization
  };
  const std::optional<Resumed>& resumed() const { return resumed_; }

  const std::vector<Particle>& particles() const { return filter_.particles(); }
  const NodeCounters& counters() const { return counters_; }
  const InputHealth& health() const { return health_; }
  std::size_t waiting_scans() const { return pending_.size(); }
  std::size_t map_memory_bytes() const { return filter_.map_memory_bytes(); }
  bool needs_objects() const { return options_.mode != LocalizerMode::kLfm; }
  // No scan has arrived for scan_timeout by `now_utime` (or none yet since `since_utime`).
  bool scans_missing(int64_t now_utime, int64_t since_utime) const;

 private:
  struct Pending {
    LaserScan scan;
    int64_t arrival_utime = 0;
    std::optional<LineObjectSet> objects;
  };
  UpdateResult process(const Pending& pending);
  std::optional<Pose2> odometry_at(int64_t utime) const;
  bool objects_missing(int64_t scan_utime) const;
  void hold_early(const LineObjectSet& objects);
  std::optional<LineObjectSet> take_early(int64_t scan_utime);
  void reset();
  void start_resumed(int64_t scan_utime);

  LocalizerOptions options_;
  ParticleFilter filter_;
  Pose2 start_pose_;
  std::vector<double> start_sigma_;
  StreamOrder scan_order_;
  StreamOrder odometry_order_;
  std::deque<std::pair<int64_t, Pose2>> odometry_;
  std::optional<Pose2> last_odometry_used_;
  std::optional<int64_t> last_processed_utime_;
  std::optional<int64_t> last_objects_utime_;
  std::optional<int64_t> first_scan_utime_;
  std::optional<int64_t> last_scan_arrival_;
  std::deque<Pending> pending_;
  std::deque<int64_t> processed_utimes_;     // the last few, to tell late objects from orphans
  std::deque<LineObjectSet> early_objects_;  // before their scan, in utime order
  struct Resume {
    Pose2 pose;
    std::vector<double> sigma;
    int64_t saved_utime = 0;
  };
  std::optional<Resume> resume_;  // until the first scan
  std::optional<Resumed> resumed_;
  InputHealth health_;
  NodeCounters counters_;
};

}  // namespace slamer

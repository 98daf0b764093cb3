// Plausibility of the localizer's inputs, checked before anything reaches
// LocalizerNode (DESIGN.md: every input is checked; what is refused is
// counted with its reason). One message must not be able to move the robot:
//   * a scan needs finite geometry, at least 3 and at most the configured
//     sensor's beams, and a utime in the stream's recent time;
//   * odometry must be finite, in the stream's time, and move no more than
//     the robot's maximum speed and yaw rate allow over the interval (plus a
//     margin); a bigger step is a jump (a driver restart, a glitch): it is
//     reported, not integrated, and the next message is the new reference;
//   * a seq that goes back while time goes on is the driver restarting (StreamRestart);
//   * INITIAL_POSE must be finite, on the map, with a positive semi-definite
//     covariance, and come at most once per `initial_pose_period`.
// A message far from its stream's time (the future, or well into the past)
// is refused, unless the stream as a whole has moved there: `confirm`
// messages in a row that agree with each other; then the stream has moved
// and the caller is told so (and may then use the ones it held back). No
// clock: times come with the messages.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "common/geometry/se2.hpp"
#include "common/sensors/laser_scan.hpp"

namespace slamer {

struct InputLimits {
  int max_beams = 1081;              // the configured sensor's
  double max_speed = 0.9;            // [m/s] the robot's
  double max_yaw_rate = 3.14;        // [rad/s]
  double odometry_margin = 0.05;     // [m and rad] on top of what speed x time allows
  double time_ahead = 2.0;           // [s] a stream may go this far ahead between two messages
  double time_back = 1.0;            // [s] and this far back (a longer step back is a new run)
  int confirm = 3;                   // messages in a row that agree: the stream has moved
  double initial_pose_period = 0.5;  // [s] at most one INITIAL_POSE per period
};

enum class TimeVerdict {
  kAccept,  // within the stream's time
  kRefuse,  // far from it: one odd message
  kMoved,   // far, but the stream has moved there: accept, and say so
};

// The time of one stream (scans or odometry).
class StreamTime {
 public:
  explicit StreamTime(const InputLimits& limits) : limits_(limits) {}
  TimeVerdict check(int64_t utime);
  // Far messages in a row that agree so far (1: the last refused one starts a new run).
  int agreeing() const { return agreeing_; }

 private:
  bool near(int64_t a, int64_t b) const;
  void accept(int64_t utime);
  InputLimits limits_;
  std::optional<int64_t> last_;
  double mean_interval_ = 0.0;        // [s] of accepted messages, smoothed
  std::optional<int64_t> candidate_;  // the last far message
  int agreeing_ = 0;
};

// A driver's restart seen in its stream: the seq goes back while the time
// goes on (a new driver process counts from 0 again; a message out of order
// goes back in both). For odometry it means a new frame: the dead reckoning
// starts over at the origin, which a small jump check cannot tell from motion
// when the robot was near it.
class StreamRestart {
 public:
  // "" or e.g. "seq 5123 -> 0 after 0.15 s" for an accepted message.
  std::string check(int64_t seq, int64_t utime);

 private:
  std::optional<int64_t> seq_;
  std::optional<int64_t> utime_;
};

// Why a scan cannot be used, or "": no time, non-finite or impossible
// geometry, fewer than 3 beams or more than the sensor has, or not one
// range within [range_min, range_max] (all NaN, inf, or 1e30).
std::string scan_problem(const LaserScan& scan, const InputLimits& limits);

// Why an odometry step from `from` (at from_utime) to `to` cannot be a real
// motion, or "" (time order is the node's business: dt <= 0 is left to it).
std::string odometry_step_problem(const Pose2& from, int64_t from_utime, const Pose2& to, int64_t to_utime,
                                  const InputLimits& limits);

// Why an INITIAL_POSE cannot be used, or "". `on_map` says whether a position lies on the map.
std::string initial_pose_problem(const Pose2& pose, const std::array<double, 9>& covariance, bool on_map);

// Counts refusals per channel and reason, for PROCESS_STATUS and a log line at most once a period.
class RefusalCounter {
 public:
  void count(const std::string& channel, const std::string& reason);
  int64_t total(const std::string& channel) const;
  // "LIDAR 3 (2 beams), ODOMETRY 1 (a jump of 3.2 m in 0.01 s)" since the last call, or "".
  std::string take_summary();

 private:
  struct Reasons {
    int64_t total = 0;
    int64_t unreported = 0;
    std::string last_reason;
  };
  std::map<std::string, Reasons> channels_;
};

}  // namespace slamer

// Scores a run the way the paper's Table I does: position and heading error
// of the estimate against ground truth (Ave / Std / Max), the fraction of
// time lost (error above a threshold), and environment-recognition accuracy
// per scan (Ave / Std / Min / Max) for the recognizer alone, the simple
// map-based method (the map's class where the estimated pose puts each
// object) and SLAMER's posterior. The true class of an object is the true
// world's at the time of the scan, where the ground-truth pose puts it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/config/config_reader.hpp"
#include "common/semantic/objects.hpp"
#include "common/stats/status_honesty.hpp"
#include "tools/sim/world.hpp"

namespace slamer {

struct PoseSample {
  PoseSample() = default;
  PoseSample(int64_t at, Pose2 p, std::optional<ReportedStatus> s = std::nullopt) : utime(at), pose(p), status(s) {}
  int64_t utime = 0;
  Pose2 pose;
  std::optional<ReportedStatus> status;  // what the estimate said of itself (POSE.status); none for dead reckoning
};

// A recognition class and what the world has where an object of it is.
struct RecognitionClass {
  std::string name;
  std::string world_class;              // empty: nothing (free space)
  std::optional<DoorState> door_state;  // for door classes
};

struct EvalOptions {
  double lost_threshold = 0.5;        // [m]
  double object_match_radius = 0.15;  // [m] how far from an object the world is looked up
  int object_samples = 5;             // points along each object that vote for its class
  std::vector<RecognitionClass> classes{
      {"open_door", "door", DoorState::kOpen},
      {"closed_door", "door", DoorState::kClosed},
      {"open_glass_door", "glass_door", DoorState::kOpen},
      {"closed_glass_door", "glass_door", DoorState::kClosed},
      {"fence", "fence", std::nullopt},
      {"no_entry_line", "no_entry_line", std::nullopt},
      {"free_space", "", std::nullopt},
      {"others", "others", std::nullopt},
  };
  int class_index(const std::string& name) const;  // -1 if absent
};
void read_options(const ConfigReader& reader, EvalOptions* options);

// Pose of a series at `utime`, interpolated on SE(2); nullopt outside it.
std::optional<Pose2> pose_at(const std::vector<PoseSample>& series, int64_t utime);

struct PoseError {
  int64_t utime = 0;
  double position = 0.0;  // [m]
  double heading = 0.0;   // [rad], absolute
  std::optional<ReportedStatus> status;
};
// One error per estimate sample that lies within the ground truth's time span.
std::vector<PoseError> pose_errors(const std::vector<PoseSample>& truth, const std::vector<PoseSample>& estimate);

struct PoseErrorStats {
  std::size_t samples = 0;
  double position_mean = 0.0, position_std = 0.0, position_max = 0.0;  // [m]
  double heading_mean = 0.0, heading_std = 0.0, heading_max = 0.0;     // [rad]
  double lost_fraction = 0.0;
};
PoseErrorStats summarize(const std::vector<PoseError>& errors, double lost_threshold);
// Issue 9's status bars over the errors, in time order; nullopt if there are
// none or any has no status (an estimate that says nothing of itself).
std::optional<StatusHonesty> status_honesty(const std::vector<PoseError>& errors);

struct AccuracyStats {
  std::size_t scans = 0;  // scans with at least one object
  std::size_t objects = 0;
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;  // per-scan accuracy, in [0, 1]
};

// Labels objects with recognition classes from a world (the true one, or the
// map as it is drawn, for the map-based method).
class ObjectLabeler {
 public:
  ObjectLabeler(const TrueWorld& world, const EvalOptions& options);
  // Class index (in options.classes) of a segment given in the map frame.
  int label(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double time) const;

 private:
  const TrueWorld& world_;
  const EvalOptions& options_;
  std::vector<int> world_to_recognition_closed_;  // per world class: recognition class when closed / stateless
  std::vector<int> world_to_recognition_open_;
  int free_space_ = -1;
};

struct RunInputs {
  std::vector<PoseSample> truth;
  std::vector<PoseSample> estimate;
  std::vector<LineObjectSet> recognized;  // LINE_OBJECTS, sensor frame
  std::vector<LineObjectSet> semantic;    // SEMANTIC_OBJECTS, map frame, same order as `recognized`
};

// Objects counted by true class (row) and predicted class (column), both
// indices into EvalOptions::classes; the last column is a prediction outside
// them (a class the evaluation does not know, or no label).
struct Confusion {
  std::vector<std::vector<int64_t>> counts;
  void add(int truth, int predicted, std::size_t classes);
  void merge(const Confusion& other);
};

struct RunScores {
  std::vector<PoseError> errors;
  PoseErrorStats pose;
  std::optional<StatusHonesty> honesty;
  AccuracyStats recognizer;
  AccuracyStats map_based;
  AccuracyStats slamer;
  // The same accuracies over only the objects where the truth's class (at the
  // true pose) differs from the map's: doors opened or closed, objects added or removed.
  AccuracyStats recognizer_differs;
  AccuracyStats map_based_differs;
  AccuracyStats slamer_differs;
  Confusion recognizer_confusion;
  Confusion map_based_confusion;
  Confusion slamer_confusion;
};

// `truth_world` is the simulation's world; `map_world` the same map with no
// truth overrides. Times for door schedules count from the first ground truth.
RunScores score_run(const RunInputs& run, const TrueWorld& truth_world, const TrueWorld& map_world,
                    const Pose2& lidar_mount, const EvalOptions& options);

}  // namespace slamer

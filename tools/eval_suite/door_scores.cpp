#include "tools/eval_suite/door_scores.hpp"

#include <map>
#include <set>

namespace slamer {

void DoorScores::merge(const DoorScores& o) {
  objects += o.objects;
  recognizer += o.recognizer;
  map_based += o.map_based;
  slamer += o.slamer;
  doors_seen += o.doors_seen;
}

DoorScores score_differing_doors(const RunInputs& run, const TrueWorld& truth_world, const TrueWorld& map_world,
                                 const Pose2& lidar_mount, const EvalOptions& options,
                                 const MapDifferences& differences, bool changing, double range) {
  DoorScores scores;
  if (run.truth.empty()) {
    return scores;
  }
  std::vector<const MapDifferences::Door*> doors;
  for (const MapDifferences::Door& d : differences.doors) {
    if (changing ? !d.changes.empty() : d.changes.empty() && d.map_state != d.truth_state) {
      doors.push_back(&d);
    }
  }
  const ObjectLabeler truth_labeler(truth_world, options);
  const ObjectLabeler map_labeler(map_world, options);
  std::map<int64_t, const LineObjectSet*> semantic;
  for (const LineObjectSet& set : run.semantic) {
    semantic[set.utime] = &set;
  }
  const auto class_of = [&](const LineObjectSet& s, int index) {
    return index >= 0 && static_cast<std::size_t>(index) < s.class_names.size()
               ? options.class_index(s.class_names[static_cast<std::size_t>(index)])
               : -2;
  };
  std::set<std::size_t> seen;
  const int64_t origin = run.truth.front().utime;
  for (const LineObjectSet& set : run.recognized) {
    const std::optional<Pose2> true_pose = pose_at(run.truth, set.utime);
    const std::optional<Pose2> estimate = pose_at(run.estimate, set.utime);
    if (!true_pose) {
      continue;
    }
    const double time = static_cast<double>(set.utime - origin) * 1e-6;
    const Pose2 sensor = compose(*true_pose, lidar_mount);
    const auto s = semantic.find(set.utime);
    const bool have_semantic = s != semantic.end() && s->second->objects.size() == set.objects.size();
    for (std::size_t i = 0; i < set.objects.size(); ++i) {
      const Eigen::Vector2d a = transform_point(sensor, set.objects[i].start);
      const Eigen::Vector2d b = transform_point(sensor, set.objects[i].end);
      for (std::size_t d = 0; d < doors.size(); ++d) {
        const MapDifferences::Door& door = *doors[d];
        if ((!door.changes.empty() && time < door.changes.front().first) ||
            (door.center - Eigen::Vector2d(sensor.x, sensor.y)).norm() > range ||
            ((a + b) / 2.0 - door.center).norm() > door.width / 2.0 + 0.3) {
          continue;
        }
        seen.insert(d);
        const int truth = truth_labeler.label(a, b, time);
        ++scores.objects;
        scores.recognizer += class_of(set, most_likely(set.objects[i].probs)) == truth ? 1 : 0;
        if (estimate) {
          const Pose2 e = compose(*estimate, lidar_mount);
          scores.map_based += map_labeler.label(transform_point(e, set.objects[i].start),
                                                transform_point(e, set.objects[i].end), time) == truth
                                  ? 1
                                  : 0;
        }
        if (have_semantic) {
          scores.slamer += class_of(*s->second, s->second->objects[i].label) == truth ? 1 : 0;
        }
        break;
      }
    }
  }
  scores.doors_seen = static_cast<int64_t>(seen.size());
  return scores;
}

}  // namespace slamer

#include "tools/eval/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace slamer {

int EvalOptions::class_index(const std::string& name) const {
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (classes[i].name == name) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void read_options(const ConfigReader& reader, EvalOptions* o) {
  reader.read("lost_threshold", &o->lost_threshold, positive());
  reader.read("object_match_radius", &o->object_match_radius, positive());
  reader.read("object_samples", &o->object_samples, in_range(1, 100));
  if (reader.has("classes")) {
    o->classes.clear();
    for (const ConfigReader& entry : reader.list("classes")) {
      RecognitionClass c;
      entry.require("name");
      entry.read("name", &c.name);
      entry.read("world_class", &c.world_class);
      if (entry.has("door_state")) {
        std::string state;
        entry.read_choice("door_state", &state, {"open", "closed"});
        c.door_state = state == "open" ? DoorState::kOpen : DoorState::kClosed;
      }
      o->classes.push_back(c);
    }
    if (o->classes.empty()) {
      reader.fail("classes", "the class table is empty");
    }
  }
}

std::optional<Pose2> pose_at(const std::vector<PoseSample>& series, int64_t utime) {
  const auto after =
      std::lower_bound(series.begin(), series.end(), utime, [](const PoseSample& s, int64_t t) { return s.utime < t; });
  if (after == series.end()) {
    return std::nullopt;
  }
  if (after->utime == utime) {
    return after->pose;
  }
  if (after == series.begin()) {
    return std::nullopt;
  }
  const PoseSample& before = *(after - 1);
  const double t = static_cast<double>(utime - before.utime) / static_cast<double>(after->utime - before.utime);
  return interpolate(before.pose, after->pose, t);
}

std::vector<PoseError> pose_errors(const std::vector<PoseSample>& truth, const std::vector<PoseSample>& estimate) {
  std::vector<PoseError> errors;
  for (const PoseSample& sample : estimate) {
    const std::optional<Pose2> true_pose = pose_at(truth, sample.utime);
    if (!true_pose) {
      continue;
    }
    errors.push_back({sample.utime, std::hypot(sample.pose.x - true_pose->x, sample.pose.y - true_pose->y),
                      std::abs(angle_diff(sample.pose.theta, true_pose->theta)), sample.status});
  }
  return errors;
}

namespace {

struct Moments {
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;
};

Moments moments(const std::vector<double>& values) {
  Moments m;
  if (values.empty()) {
    return m;
  }
  double sum = 0.0;
  for (const double v : values) {
    sum += v;
  }
  m.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values) {
    squares += (v - m.mean) * (v - m.mean);
  }
  m.std = std::sqrt(squares / static_cast<double>(values.size()));
  m.min = *std::min_element(values.begin(), values.end());
  m.max = *std::max_element(values.begin(), values.end());
  return m;
}

AccuracyStats accuracy(const std::vector<std::pair<int, int>>& correct_and_total) {
  AccuracyStats stats;
  std::vector<double> per_scan;
  for (const auto& [correct, total] : correct_and_total) {
    if (total > 0) {
      per_scan.push_back(static_cast<double>(correct) / total);
      stats.objects += static_cast<std::size_t>(total);
    }
  }
  stats.scans = per_scan.size();
  const Moments m = moments(per_scan);
  stats.mean = m.mean;
  stats.std = m.std;
  stats.min = m.min;
  stats.max = m.max;
  return stats;
}

}  // namespace

PoseErrorStats summarize(const std::vector<PoseError>& errors, double lost_threshold) {
  PoseErrorStats stats;
  stats.samples = errors.size();
  std::vector<double> positions;
  std::vector<double> headings;
  std::size_t lost = 0;
  for (const PoseError& e : errors) {
    positions.push_back(e.position);
    headings.push_back(e.heading);
    lost += e.position > lost_threshold ? 1 : 0;
  }
  const Moments p = moments(positions);
  const Moments h = moments(headings);
  stats.position_mean = p.mean;
  stats.position_std = p.std;
  stats.position_max = p.max;
  stats.heading_mean = h.mean;
  stats.heading_std = h.std;
  stats.heading_max = h.max;
  stats.lost_fraction = errors.empty() ? 0.0 : static_cast<double>(lost) / static_cast<double>(errors.size());
  return stats;
}

ObjectLabeler::ObjectLabeler(const TrueWorld& world, const EvalOptions& options) : world_(world), options_(options) {
  const SemanticMap& map = world.map();
  world_to_recognition_closed_.assign(map.classes.size(), -1);
  world_to_recognition_open_.assign(map.classes.size(), -1);
  for (std::size_t r = 0; r < options.classes.size(); ++r) {
    const RecognitionClass& c = options.classes[r];
    if (c.world_class.empty()) {
      free_space_ = static_cast<int>(r);
      continue;
    }
    const int w = map.class_index(c.world_class);
    if (w < 0) {
      continue;
    }
    if (!c.door_state || *c.door_state == DoorState::kClosed) {
      world_to_recognition_closed_[static_cast<std::size_t>(w)] = static_cast<int>(r);
    }
    if (!c.door_state || *c.door_state == DoorState::kOpen) {
      world_to_recognition_open_[static_cast<std::size_t>(w)] = static_cast<int>(r);
    }
  }
}

int ObjectLabeler::label(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double time) const {
  std::map<int, int> votes;
  const int samples = options_.object_samples;
  for (int i = 0; i < samples; ++i) {
    const double t = samples == 1 ? 0.5 : static_cast<double>(i) / (samples - 1);
    const Eigen::Vector2d p = start + t * (end - start);
    int door = -1;
    const int world_class = world_.class_near(p, options_.object_match_radius, &door);
    int recognition = free_space_;
    if (world_class >= 0) {
      // The state of the door the matched cell belongs to (p itself may lie just off it).
      const bool open = door >= 0 && world_.door_state(door, time) == DoorState::kOpen;
      recognition =
          (open ? world_to_recognition_open_ : world_to_recognition_closed_)[static_cast<std::size_t>(world_class)];
    }
    ++votes[recognition];
  }
  // Most votes; ties go to the smaller index so the result does not depend on order.
  int best = -1;
  int best_votes = 0;
  for (const auto& [label, count] : votes) {
    if (count > best_votes) {
      best = label;
      best_votes = count;
    }
  }
  return best;
}

void Confusion::add(int truth, int predicted, std::size_t classes) {
  if (counts.empty()) {
    counts.assign(classes, std::vector<int64_t>(classes + 1, 0));
  }
  if (truth < 0 || static_cast<std::size_t>(truth) >= classes) {
    return;
  }
  const std::size_t column =
      predicted >= 0 && static_cast<std::size_t>(predicted) < classes ? static_cast<std::size_t>(predicted) : classes;
  ++counts[static_cast<std::size_t>(truth)][column];
}

void Confusion::merge(const Confusion& other) {
  if (counts.empty()) {
    counts = other.counts;
    return;
  }
  for (std::size_t r = 0; r < other.counts.size() && r < counts.size(); ++r) {
    for (std::size_t c = 0; c < other.counts[r].size() && c < counts[r].size(); ++c) {
      counts[r][c] += other.counts[r][c];
    }
  }
}

std::optional<StatusHonesty> status_honesty(const std::vector<PoseError>& errors) {
  if (errors.empty()) {
    return std::nullopt;
  }
  StatusHonesty honesty;
  for (const PoseError& e : errors) {
    if (!e.status) {
      return std::nullopt;
    }
    honesty.add(static_cast<double>(e.utime) * 1e-6, e.position, *e.status);
  }
  return honesty;
}

RunScores score_run(const RunInputs& run, const TrueWorld& truth_world, const TrueWorld& map_world,
                    const Pose2& lidar_mount, const EvalOptions& options) {
  RunScores scores;
  scores.errors = pose_errors(run.truth, run.estimate);
  scores.pose = summarize(scores.errors, options.lost_threshold);
  scores.honesty = status_honesty(scores.errors);
  if (run.truth.empty()) {
    return scores;
  }
  const int64_t time_origin = run.truth.front().utime;
  const ObjectLabeler truth_labeler(truth_world, options);
  const ObjectLabeler map_labeler(map_world, options);
  std::map<int64_t, const LineObjectSet*> semantic_by_utime;
  for (const LineObjectSet& set : run.semantic) {
    semantic_by_utime[set.utime] = &set;
  }
  std::vector<std::pair<int, int>> recognizer;
  std::vector<std::pair<int, int>> map_based;
  std::vector<std::pair<int, int>> slamer;
  std::vector<std::pair<int, int>> recognizer_differs;
  std::vector<std::pair<int, int>> map_differs;
  std::vector<std::pair<int, int>> slamer_differs;
  const std::size_t classes = options.classes.size();
  const auto class_of = [&](const LineObjectSet& s, int index) {
    return index >= 0 && static_cast<std::size_t>(index) < s.class_names.size()
               ? options.class_index(s.class_names[static_cast<std::size_t>(index)])
               : -2;  // no label: never right
  };
  for (const LineObjectSet& set : run.recognized) {
    const std::optional<Pose2> true_pose = pose_at(run.truth, set.utime);
    if (!true_pose || set.objects.empty()) {
      continue;
    }
    const double time = static_cast<double>(set.utime - time_origin) * 1e-6;
    const Pose2 true_sensor = compose(*true_pose, lidar_mount);
    const std::optional<Pose2> estimate = pose_at(run.estimate, set.utime);
    const auto semantic = semantic_by_utime.find(set.utime);
    const bool have_semantic =
        semantic != semantic_by_utime.end() && semantic->second->objects.size() == set.objects.size();
    int correct_recognizer = 0;
    int correct_map = 0;
    int correct_slamer = 0;
    int differing = 0, differing_recognizer = 0, differing_map = 0, differing_slamer = 0;
    for (std::size_t i = 0; i < set.objects.size(); ++i) {
      const LineObject& object = set.objects[i];
      const Eigen::Vector2d true_start = transform_point(true_sensor, object.start);
      const Eigen::Vector2d true_end = transform_point(true_sensor, object.end);
      const int truth = truth_labeler.label(true_start, true_end, time);
      const bool differs = map_labeler.label(true_start, true_end, time) != truth;
      differing += differs ? 1 : 0;
      const int predicted = class_of(set, most_likely(object.probs));
      scores.recognizer_confusion.add(truth, predicted, classes);
      correct_recognizer += predicted == truth ? 1 : 0;
      differing_recognizer += differs && predicted == truth ? 1 : 0;
      if (estimate) {
        const Pose2 sensor = compose(*estimate, lidar_mount);
        const int mapped =
            map_labeler.label(transform_point(sensor, object.start), transform_point(sensor, object.end), time);
        scores.map_based_confusion.add(truth, mapped, classes);
        correct_map += mapped == truth ? 1 : 0;
        differing_map += differs && mapped == truth ? 1 : 0;
      }
      if (have_semantic) {
        const int label = class_of(*semantic->second, semantic->second->objects[i].label);
        scores.slamer_confusion.add(truth, label, classes);
        correct_slamer += label == truth ? 1 : 0;
        differing_slamer += differs && label == truth ? 1 : 0;
      }
    }
    if (differing > 0) {
      recognizer_differs.emplace_back(differing_recognizer, differing);
      if (estimate) {
        map_differs.emplace_back(differing_map, differing);
      }
      if (have_semantic) {
        slamer_differs.emplace_back(differing_slamer, differing);
      }
    }
    const int total = static_cast<int>(set.objects.size());
    recognizer.emplace_back(correct_recognizer, total);
    if (estimate) {
      map_based.emplace_back(correct_map, total);
    }
    if (have_semantic) {
      slamer.emplace_back(correct_slamer, total);
    }
  }
  scores.recognizer = accuracy(recognizer);
  scores.map_based = accuracy(map_based);
  scores.slamer = accuracy(slamer);
  scores.recognizer_differs = accuracy(recognizer_differs);
  scores.map_based_differs = accuracy(map_differs);
  scores.slamer_differs = accuracy(slamer_differs);
  return scores;
}

}  // namespace slamer

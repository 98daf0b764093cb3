#include "tools/eval/recognizer_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "localizer/recognition_model.hpp"
#include "recognizer/line_recognizer.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/pose_estimate_t.hpp"

namespace slamer {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", v);
  return text;
}

}  // namespace

std::vector<ClassRule> bin_rules() {
  const std::vector<double> coverage{0.0, 0.35, 0.55, 0.75, 0.9, 1.0};
  const std::vector<double> physical_length{0.0, 0.8, 1.3, 2.0, 1e9};
  const std::vector<double> spatial_length{0.0, 0.85, 1.15, 1.5, 2.0, 1e9};
  std::vector<ClassRule> rules;
  for (std::size_t c = 0; c + 1 < coverage.size(); ++c) {
    for (std::size_t l = 0; l + 1 < physical_length.size(); ++l) {
      rules.push_back(
          {LineKind::kPhysical, coverage[c], coverage[c + 1], physical_length[l], physical_length[l + 1], {}});
    }
  }
  for (std::size_t l = 0; l + 1 < spatial_length.size(); ++l) {
    rules.push_back({LineKind::kSpatial, 0.0, 1.0, spatial_length[l], spatial_length[l + 1], {}});
  }
  return rules;
}

std::vector<LabelledObject> labelled_objects(const std::string& world_file, const std::vector<std::string>& logs,
                                             const RecognizerProcessConfig& config, const EvalConfig& eval,
                                             std::string* problems) {
  const auto world_options = load_options<WorldOptions>(world_file);
  const auto robot = load_options<RobotOptions>(world_options.robot_path);
  const TrueWorld world(load_semantic_map(world_options.map_path), world_options, world_file);
  const ObjectLabeler labeler(world, eval.eval);
  const LineRecognizer current(config.recognizer);
  RecognizerOptions binned = config.recognizer;
  binned.rules = bin_rules();
  const std::vector<std::string>& classes = config.recognizer.classes;
  std::vector<LabelledObject> objects;
  for (const std::string& path : logs) {
    EventLogReader log(path);
    std::map<int64_t, Pose2> truth;
    int64_t time_origin = -1;
    while (const std::optional<LogEvent> e = log.next()) {
      const auto size = e->data.size();
      if (e->channel == eval.channels.ground_truth) {
        pose_estimate_t m{};
        if (decode_message(e->data.data(), size, &m) == DecodeStatus::kOk) {
          truth[m.utime] = {m.x, m.y, m.theta};
          time_origin = time_origin < 0 ? m.utime : time_origin;
        }
        continue;
      }
      laser_scan_t m{};
      if (e->channel != config.lidar_channel || decode_message(e->data.data(), size, &m) != DecodeStatus::kOk) {
        continue;
      }
      const auto pose = truth.find(m.utime);
      if (pose == truth.end()) {
        continue;
      }
      const Pose2 sensor = compose(pose->second, robot.lidar.mount);
      const double time = static_cast<double>(m.utime - time_origin) * 1e-6;
      for (const RecognizedLine& line : current.recognize_with_features(from_message(m))) {
        const int label =
            labeler.label(transform_point(sensor, line.object.start), transform_point(sensor, line.object.end), time);
        const std::string name = label >= 0 ? eval.eval.classes[static_cast<std::size_t>(label)].name : "";
        const auto it = std::find(classes.begin(), classes.end(), name);
        if (it == classes.end()) {
          continue;
        }
        LabelledObject object;
        object.truth = static_cast<int>(it - classes.begin());
        object.bin =
            matching_rule(line.object.kind, line.coverage, (line.object.end - line.object.start).norm(), binned);
        object.right_before = most_likely(line.object.probs) == object.truth;
        objects.push_back(object);
      }
    }
    if (problems != nullptr && !log.problems().empty()) {
      *problems += (problems->empty() ? "" : "; ") + log.problems();
    }
  }
  return objects;
}

FittedRules fit_rules(const std::vector<LabelledObject>& objects, const std::vector<std::string>& classes,
                      double prior) {
  const std::vector<ClassRule> bins = bin_rules();
  const std::size_t k = classes.size();
  std::vector<std::vector<double>> counts(bins.size(), std::vector<double>(k, 0.0));
  for (const LabelledObject& o : objects) {
    if (o.bin >= 0 && o.truth >= 0 && static_cast<std::size_t>(o.truth) < k) {
      counts[static_cast<std::size_t>(o.bin)][static_cast<std::size_t>(o.truth)] += 1.0;
    }
  }
  FittedRules fitted;
  fitted.probs.resize(bins.size());
  fitted.class_prior.assign(k, 0.0);
  double objects_total = 0.0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    double total = 0.0;
    for (const double c : counts[b]) {
      total += c;
    }
    if (total <= 0.0) {
      continue;
    }
    ClassRule rule = bins[b];
    for (std::size_t c = 0; c < k; ++c) {
      const double p = (counts[b][c] + prior) / (total + prior * static_cast<double>(k));
      rule.probs[classes[c]] = p;
      fitted.probs[b].push_back(p);
      fitted.class_prior[c] += total * p;
    }
    objects_total += total;
    fitted.right += static_cast<int64_t>(*std::max_element(counts[b].begin(), counts[b].end()));
    fitted.rules.push_back(rule);
    fitted.objects.push_back(static_cast<int64_t>(total));
  }
  for (double& p : fitted.class_prior) {
    p = objects_total > 0.0 ? p / objects_total : 1.0 / static_cast<double>(k);
  }
  return fitted;
}

double fit_temperature(const std::vector<HeldOut>& folds, double min_probability) {
  // Objects of one bin and truth add the same term: count them once.
  struct Tally {
    std::vector<double> log_q;  // per class
    const std::vector<double>* prior;
    std::size_t truth;
    double count;
  };
  std::vector<Tally> tallies;
  for (const HeldOut& fold : folds) {
    std::map<std::pair<int, int>, double> counts;  // (bin, truth)
    for (const LabelledObject& o : *fold.objects) {
      if (o.bin >= 0 && !fold.rules->probs[static_cast<std::size_t>(o.bin)].empty()) {
        counts[{o.bin, o.truth}] += 1.0;
      }
    }
    for (const auto& [key, count] : counts) {
      const std::vector<double>& p = fold.rules->probs[static_cast<std::size_t>(key.first)];
      const std::vector<float> q =
          divide_out_prior(std::vector<float>(p.begin(), p.end()), fold.rules->class_prior, min_probability);
      Tally tally{{}, &fold.rules->class_prior, static_cast<std::size_t>(key.second), count};
      for (const float v : q) {
        tally.log_q.push_back(std::log(std::max(static_cast<double>(v), min_probability)));
      }
      tallies.push_back(std::move(tally));
    }
  }
  // The objective is concave in t (a linear term minus a log-sum-exp): a fine
  // grid finds its maximum.
  double best_t = 1.0;
  double best = -std::numeric_limits<double>::infinity();
  for (int step = 1; step <= 120; ++step) {
    const double t = 0.05 * step;
    double sum = 0.0;
    for (const Tally& tally : tallies) {
      double norm = 0.0;
      for (std::size_t l = 0; l < tally.log_q.size(); ++l) {
        norm += (*tally.prior)[l] * std::exp(t * tally.log_q[l]);
      }
      sum += tally.count * (std::log((*tally.prior)[tally.truth]) + t * tally.log_q[tally.truth] - std::log(norm));
    }
    if (sum > best) {
      best = sum;
      best_t = t;
    }
  }
  return best_t;
}

std::string rules_yaml(const FittedRules& fitted, const std::vector<std::string>& classes) {
  std::ostringstream out;
  int64_t total = 0;
  for (const int64_t n : fitted.objects) {
    total += n;
  }
  out << "  rules:   # fitted by slamer-calibrate-recognizer on " << total << " objects\n";
  for (std::size_t r = 0; r < fitted.rules.size(); ++r) {
    const ClassRule& rule = fitted.rules[r];
    out << "    - {kind: " << (rule.kind == LineKind::kPhysical ? "physical" : "spatial");
    if (rule.kind == LineKind::kPhysical) {
      out << ", min_coverage: " << number(rule.min_coverage) << ", max_coverage: " << number(rule.max_coverage);
    }
    out << ", min_length: " << number(rule.min_length);
    if (rule.max_length < 1e8) {
      out << ", max_length: " << number(rule.max_length);
    }
    out << ", probs: {";
    for (std::size_t c = 0; c < classes.size(); ++c) {
      out << (c == 0 ? "" : ", ") << classes[c] << ": " << number(rule.probs.at(classes[c]));
    }
    out << "}}   # " << fitted.objects[r] << " objects\n";
  }
  return out.str();
}

std::string training_prior_yaml(const FittedRules& fitted, const std::vector<std::string>& classes) {
  std::ostringstream out;
  out << "    training_prior:\n";
  for (std::size_t c = 0; c < classes.size() && c < fitted.class_prior.size(); ++c) {
    out << "      " << classes[c] << ": " << number(fitted.class_prior[c]) << "\n";
  }
  return out.str();
}

}  // namespace slamer

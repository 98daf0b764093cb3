// slamer-calibrate-recognizer: fits the recognizer's class rules to simulated
// runs. Every recognized object is put in a feature bin (kind, coverage and
// length for physical lines; length for spatial ones) and labelled with the
// true world's class where the ground-truth pose puts it; each bin's rule
// gets the class frequencies seen in it (with a small prior), which is what
// makes the recognizer's most likely class the most often right one.
// Prints the rules as YAML for config/recognizer.yaml and the accuracies on stderr.
#include <cstdio>
#include <iostream>
#include <map>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log.hpp"
#include "common/process/process_main.hpp"
#include "recognizer/line_recognizer.hpp"
#include "recognizer/recognizer_config.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "tools/eval/eval_config.hpp"

namespace slamer {
namespace {

// The rule grid: one rule per bin.
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

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", v);
  return text;
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-calibrate-recognizer",
      "Fits the recognizer's class rules to simulated logs (LIDAR + GROUND_TRUTH) of a world and prints\n"
      "them as YAML for the recognizer config; accuracies before and after go to stderr.",
      [](slamer::CommandLine& cli) {
        cli.add_option("world", "FILE", "the world the logs were simulated in");
        cli.add_option("eval-config", "FILE", "class meanings (config/eval.yaml)");
        cli.add_option("prior", "A", "pseudo-count added to every class of a bin", "0.5");
        cli.set_positional("LOG", "simulated logs", 1, 32);
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("world")) {
          throw slamer::CommandLineError("--world FILE is required");
        }
        const auto config = slamer::load_config<slamer::RecognizerProcessConfig>(cli);
        slamer::EvalConfig eval;
        if (cli.has("eval-config")) {
          eval = slamer::load_options<slamer::EvalConfig>(cli.get("eval-config"));
        }
        const double prior = cli.get_double("prior");
        const auto world_options = slamer::load_options<slamer::WorldOptions>(cli.get("world"));
        const auto robot = slamer::load_options<slamer::RobotOptions>(world_options.robot_path);
        const slamer::TrueWorld world(slamer::load_semantic_map(world_options.map_path), world_options,
                                      cli.get("world"));
        const slamer::ObjectLabeler labeler(world, eval.eval);
        const slamer::LineRecognizer current(config.recognizer);
        slamer::RecognizerOptions binned = config.recognizer;
        binned.rules = slamer::bin_rules();
        const std::size_t classes = config.recognizer.classes.size();
        std::vector<std::vector<double>> counts(binned.rules.size(), std::vector<double>(classes, 0.0));
        int64_t objects = 0;
        int64_t right_before = 0;
        std::vector<std::pair<int, int>> samples;  // (bin, true class index in recognizer classes)
        for (const std::string& path : cli.positional()) {
          slamer::EventLogReader log(path);
          std::map<int64_t, slamer::Pose2> truth;
          int64_t time_origin = -1;
          while (const std::optional<slamer::LogEvent> e = log.next()) {
            const auto size = e->data.size();
            if (e->channel == eval.channels.ground_truth) {
              slamer::pose_estimate_t m{};
              if (slamer::decode_message(e->data.data(), size, &m) == slamer::DecodeStatus::kOk) {
                truth[m.utime] = {m.x, m.y, m.theta};
                time_origin = time_origin < 0 ? m.utime : time_origin;
              }
            } else if (e->channel == config.lidar_channel) {
              slamer::laser_scan_t m{};
              if (slamer::decode_message(e->data.data(), size, &m) != slamer::DecodeStatus::kOk) {
                continue;
              }
              const auto pose = truth.find(m.utime);
              if (pose == truth.end()) {
                continue;
              }
              const slamer::Pose2 sensor = slamer::compose(pose->second, robot.lidar.mount);
              const double time = static_cast<double>(m.utime - time_origin) * 1e-6;
              for (const slamer::RecognizedLine& line : current.recognize_with_features(slamer::from_message(m))) {
                const int label = labeler.label(slamer::transform_point(sensor, line.object.start),
                                                slamer::transform_point(sensor, line.object.end), time);
                const auto name = label >= 0 ? eval.eval.classes[static_cast<std::size_t>(label)].name : "";
                const auto it = std::find(config.recognizer.classes.begin(), config.recognizer.classes.end(), name);
                if (it == config.recognizer.classes.end()) {
                  continue;
                }
                const int truth_class = static_cast<int>(it - config.recognizer.classes.begin());
                const double length = (line.object.end - line.object.start).norm();
                const int bin = slamer::matching_rule(line.object.kind, line.coverage, length, binned);
                ++objects;
                right_before += slamer::most_likely(line.object.probs) == truth_class ? 1 : 0;
                if (bin >= 0) {
                  counts[static_cast<std::size_t>(bin)][static_cast<std::size_t>(truth_class)] += 1.0;
                  samples.emplace_back(bin, truth_class);
                }
              }
            }
          }
          if (!log.problems().empty()) {
            slamer::log_line("slamer-calibrate-recognizer", slamer::LogLevel::kWarning, log.problems());
          }
        }
        // Rules from the counts; accuracy of their most likely class on the same objects.
        int64_t right_after = 0;
        std::cout << "  rules:   # fitted by slamer-calibrate-recognizer on " << objects << " objects\n";
        for (std::size_t b = 0; b < binned.rules.size(); ++b) {
          double total = 0.0;
          for (const double c : counts[b]) {
            total += c;
          }
          if (total <= 0.0) {
            continue;
          }
          const slamer::ClassRule& rule = binned.rules[b];
          std::size_t best = 0;
          for (std::size_t c = 0; c < classes; ++c) {
            best = counts[b][c] > counts[b][best] ? c : best;
          }
          right_after += static_cast<int64_t>(counts[b][best]);
          std::cout << "    - {kind: " << (rule.kind == slamer::LineKind::kPhysical ? "physical" : "spatial");
          if (rule.kind == slamer::LineKind::kPhysical) {
            std::cout << ", min_coverage: " << slamer::number(rule.min_coverage)
                      << ", max_coverage: " << slamer::number(rule.max_coverage);
          }
          std::cout << ", min_length: " << slamer::number(rule.min_length);
          if (rule.max_length < 1e8) {
            std::cout << ", max_length: " << slamer::number(rule.max_length);
          }
          std::cout << ", probs: {";
          for (std::size_t c = 0; c < classes; ++c) {
            std::cout << (c == 0 ? "" : ", ") << config.recognizer.classes[c] << ": "
                      << slamer::number((counts[b][c] + prior) / (total + prior * static_cast<double>(classes)));
          }
          std::cout << "}}   # " << static_cast<int64_t>(total) << " objects\n";
        }
        std::fprintf(stderr, "objects: %lld; most likely class right: %.1f %% with the given rules, %.1f %% fitted\n",
                     static_cast<long long>(objects),
                     100.0 * static_cast<double>(right_before) / std::max<int64_t>(objects, 1),
                     100.0 * static_cast<double>(right_after) / std::max<int64_t>(objects, 1));
        return 0;
      });
}

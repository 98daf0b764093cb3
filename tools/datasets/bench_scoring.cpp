#include "tools/datasets/bench_scoring.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace slamer {
namespace {

// Issue 9's bands, the same as the honesty count's.
constexpr double kLost = StatusHonesty::kFar;
constexpr double kClose = StatusHonesty::kClose;
// Off by at most this for under 2 s after being right: a blip (of the reference or a scan match),
// not another place.
constexpr double kBlip = 1.0;  // [m]

ErrorStats stats_of(const std::vector<double>& values) {
  ErrorStats s;
  if (values.empty()) {
    return s;
  }
  double sum = 0.0;
  for (const double v : values) {
    sum += v;
    s.max = std::max(s.max, v);
  }
  s.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values) {
    squares += (v - s.mean) * (v - s.mean);
  }
  s.std = std::sqrt(squares / static_cast<double>(values.size()));
  return s;
}

nlohmann::json to_json(const ErrorStats& s, double scale) {
  return {{"mean", s.mean * scale}, {"std", s.std * scale}, {"max", s.max * scale}};
}

}  // namespace

const char* status_name(BenchStatus status) {
  switch (status) {
    case BenchStatus::kInitializing:
      return "INITIALIZING";
    case BenchStatus::kOk:
      return "OK";
    case BenchStatus::kUncertain:
      return "UNCERTAIN";
    case BenchStatus::kLost:
      return "LOST";
  }
  return "LOST";
}

std::vector<BenchPose> poses_per_scan(const std::vector<int64_t>& scan_utimes, const std::vector<int64_t>& log_utimes,
                                      const std::vector<PoseReport>& reports, const Pose2& initial_pose,
                                      int64_t* missing) {
  std::vector<PoseReport> sorted = reports;
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.utime < b.utime; });
  std::vector<BenchPose> poses;
  BenchPose previous{0.0, initial_pose, BenchStatus::kInitializing, false, 0};
  *missing = 0;
  for (std::size_t k = 0; k < scan_utimes.size(); ++k) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), scan_utimes[k],
                                     [](const PoseReport& r, int64_t t) { return r.utime < t; });
    BenchPose pose = previous;
    pose.t = static_cast<double>(k < log_utimes.size() ? log_utimes[k] : scan_utimes[k]) * 1e-6;
    pose.utime = scan_utimes[k];
    if (it != sorted.end() && it->utime == scan_utimes[k]) {
      pose.pose = it->pose;
      pose.status = it->status;
      pose.has_report = true;
    } else {
      pose.has_report = false;
      ++*missing;
    }
    poses.push_back(pose);
    previous = pose;
  }
  return poses;
}

BenchScore score_poses(const std::vector<BenchPose>& poses, const std::vector<Pose2>& reference) {
  if (poses.size() != reference.size()) {
    throw std::invalid_argument("score_poses: one reference pose per scan is needed");
  }
  BenchScore score;
  score.scans = static_cast<int64_t>(poses.size());
  std::vector<double> headings;
  int64_t lost = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double e = std::hypot(poses[k].pose.x - reference[k].x, poses[k].pose.y - reference[k].y);
    score.position_errors.push_back(e);
    headings.push_back(std::abs(angle_diff(poses[k].pose.theta, reference[k].theta)));
    lost += e > kLost ? 1 : 0;
    score.scans_without_pose += poses[k].has_report ? 0 : 1;
    const int column = e < kClose ? 0 : (e <= kLost ? 1 : 2);
    ++score.confusion[static_cast<std::size_t>(poses[k].status)][static_cast<std::size_t>(column)];
    // By utime: csail's own times stand still, a kidnapped log's jump over the carry.
    score.honesty.add(static_cast<double>(poses[k].utime) * 1e-6, e, poses[k].status);
  }
  score.position = stats_of(score.position_errors);
  score.heading = stats_of(headings);
  score.fraction_lost = poses.empty() ? 0.0 : static_cast<double>(lost) / static_cast<double>(poses.size());
  // Back from the end: stop at a stretch off by more than 0.5 m that is not a blip (it lasted the
  // honesty grace, went more than 1 m off, or began at the first scan: a global localization's search).
  std::size_t right = 0;
  for (std::size_t k = poses.size(); k > 0; --k) {
    if (score.position_errors[k - 1] <= kLost) {
      continue;
    }
    std::size_t first = k - 1;
    double worst = score.position_errors[first];
    while (first > 0 && score.position_errors[first - 1] > kLost) {
      --first;
      worst = std::max(worst, score.position_errors[first]);
    }
    if (k == poses.size() || first == 0 || worst > kBlip ||
        static_cast<double>(poses[k].utime - poses[first].utime) * 1e-6 >= StatusHonesty::kGraceSeconds) {
      right = k;
      break;
    }
    score.far_after_right += static_cast<int64_t>(k - first);
    k = first + 1;
  }
  if (right < poses.size()) {
    score.right_from = static_cast<int64_t>(right);
    score.right_from_seconds = static_cast<double>(poses[right].utime - poses.front().utime) * 1e-6;
    for (std::size_t k = right; k < poses.size(); ++k) {
      if (poses[k].status == BenchStatus::kOk) {
        score.ok_from = static_cast<int64_t>(k);
        score.ok_from_seconds = static_cast<double>(poses[k].utime - poses.front().utime) * 1e-6;
        break;
      }
    }
  }
  return score;
}

std::string format_poses(const std::vector<BenchPose>& poses) {
  std::string text;
  char line[160];
  for (const BenchPose& p : poses) {
    std::snprintf(line, sizeof line, "%.6f %.4f %.4f %.5f %s\n", p.t, p.pose.x, p.pose.y, p.pose.theta,
                  status_name(p.status));
    text += line;
  }
  return text;
}

std::string describe_right_from(const BenchScore& score) {
  const auto at = [](const std::optional<int64_t>& scan, double seconds) {
    char when[64] = "never";
    if (scan) {
      std::snprintf(when, sizeof when, "scan %lld (%.1f s)", static_cast<long long>(*scan), seconds);
    }
    return std::string(when);
  };
  return "within 0.5 m to the end from " + at(score.right_from, score.right_from_seconds) + " (then " +
         std::to_string(score.far_after_right) + " scans in blips: <= 1 m off, < 2 s), OK from " +
         at(score.ok_from, score.ok_from_seconds) + "; OK while > 0.5 m off in " +
         std::to_string(score.confusion[1][2]) + " scans";
}

std::string describe_score(const BenchScore& score, const BenchRunInfo& info) {
  char text[400];
  std::snprintf(
      text, sizeof text,
      "%lld scans: position error mean %.1f cm (std %.1f, max %.1f), heading %.2f deg, lost %.1f %%, "
      "status: %.1f %% of %lld far flagged after 2 s, %.2f %% of close LOST, "
      "%.3f ms per scan (CPU, start-up excluded)",
      static_cast<long long>(score.scans), score.position.mean * 100, score.position.std * 100,
      score.position.max * 100, score.heading.mean * 180 / 3.14159265358979, score.fraction_lost * 100,
      score.honesty.far_flagged_fraction() * 100, static_cast<long long>(score.honesty.far_after_grace()),
      score.honesty.close_lost_fraction() * 100,
      std::max(0.0, info.cpu_seconds - info.startup_cpu_seconds) / std::max<double>(1, score.scans - 1) * 1e3);
  return text;
}

std::string summary_json(const BenchScore& score, const BenchRunInfo& info) {
  nlohmann::json confusion;
  for (int s = 0; s < 4; ++s) {
    const auto& row = score.confusion[static_cast<std::size_t>(s)];
    confusion[status_name(static_cast<BenchStatus>(s))] = {
        {"error_below_0.2m", row[0]}, {"error_0.2_to_0.5m", row[1]}, {"error_above_0.5m", row[2]}};
  }
  const double scans = static_cast<double>(std::max<int64_t>(score.scans, 1));
  const auto scan_or_null = [](const std::optional<int64_t>& scan) {
    return scan ? nlohmann::json(*scan) : nlohmann::json(nullptr);
  };
  const nlohmann::json json = {
      {"log", info.log},
      {"reference", "the log's corrected poses (GMapping's estimate, not ground truth)"},
      {"mode", info.mode},
      {"particles", info.particles},
      {"beams", info.beams},
      {"seed", info.seed},
      {"start", info.global ? "global localization" : "the first reference pose"},
      {"kidnap", info.kidnap ? nlohmann::json{{"from_scan", info.kidnap->first},
                                              {"to_scan", info.kidnap->second},
                                              {"note",
                                               "the robot carried unseen: the log's scans from_scan to to_scan - 1 "
                                               "left out (the map keeps them); scans and the scores count the scans "
                                               "kept; poses.txt has every scan of the log, a carried one with "
                                               "the pose before the carry"}}
                             : nlohmann::json(nullptr)},
      {"scans", score.scans},
      {"scans_without_pose", score.scans_without_pose},
      {"position_error_m", to_json(score.position, 1.0)},
      {"heading_error_deg", to_json(score.heading, 180.0 / 3.14159265358979323846)},
      {"fraction_lost", score.fraction_lost},
      {"lost_threshold_m", kLost},
      {"right_from",
       {{"scan", scan_or_null(score.right_from)},
        {"seconds", score.right_from_seconds},
        {"ok_scan", scan_or_null(score.ok_from)},
        {"ok_seconds", score.ok_from_seconds},
        {"far_scans_after", score.far_after_right},
        {"note",
         "the first scan (0-based) from which the position error is <= 0.5 m to the end but for blips (off by "
         "at most 1 m for under 2 s; far_scans_after counts their scans), and the first scan from there that "
         "says OK; null: never; seconds from the first scan"}}},
      {"time_per_scan_ms",
       {{"wall", info.wall_seconds / scans * 1e3},
        {"cpu", info.cpu_seconds / scans * 1e3},
        {"cpu_without_startup",
         std::max(0.0, info.cpu_seconds - info.startup_cpu_seconds) / std::max(1.0, scans - 1.0) * 1e3},
        {"note",
         "wall and cpu: the whole localizer process over the scans; cpu_without_startup: minus a run on "
         "the first scan alone (map loading, field building)"}}},
      {"status_vs_error", confusion},
      {"status_honesty",
       {{"far_scans_after_2s", score.honesty.far_after_grace()},
        {"far_flagged_after_2s", score.honesty.far_after_grace_flagged()},
        {"far_flagged_fraction", score.honesty.far_flagged_fraction()},
        {"close_scans", score.honesty.close()},
        {"close_lost_fraction", score.honesty.close_lost_fraction()},
        {"note",
         "of the scans > 0.5 m off, 2 s or more after the error passed 0.5 m: the fraction saying UNCERTAIN "
         "or LOST (goal >= 0.9); of the scans < 0.2 m off: the fraction saying LOST (goal < 0.01)"}}},
      {"localizer_command", info.command},
  };
  return json.dump(2) + "\n";
}

void write_bench_plot(const std::vector<BenchPose>& poses, const BenchScore& score, const std::string& title,
                      const std::string& png_path) {
  const int width = 1200;
  const int height = 480;
  const int left = 70;
  const int right = 20;
  const int top = 40;
  const int strip = 24;
  const int bottom = 50 + strip;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const double max_error = std::max(1.0, std::ceil(score.position.max));
  const double t0 = poses.empty() ? 0.0 : poses.front().t;
  const double t1 = poses.empty() ? 1.0 : std::max(poses.back().t, t0 + 1e-6);
  const auto px = [&](double t) { return left + static_cast<int>((t - t0) / (t1 - t0) * (width - left - right)); };
  const auto py = [&](double e) {
    return top + static_cast<int>((1.0 - std::min(e, max_error) / max_error) * (height - top - bottom));
  };
  const cv::Scalar colours[4] = {{160, 160, 160}, {80, 180, 80}, {0, 190, 255}, {0, 0, 230}};  // BGR
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const int x0 = px(poses[k].t);
    const int x1 = k + 1 < poses.size() ? px(poses[k + 1].t) : x0 + 1;
    cv::rectangle(image, {x0, height - bottom + 6}, {std::max(x1, x0 + 1), height - bottom + 6 + strip},
                  colours[static_cast<int>(poses[k].status)], cv::FILLED);
  }
  const int y_lost = py(kLost);
  cv::line(image, {left, y_lost}, {width - right, y_lost}, {0, 0, 230}, 1);
  cv::putText(image, "0.5 m", {width - right - 50, y_lost - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 230});
  for (std::size_t k = 1; k < poses.size(); ++k) {
    cv::line(image, {px(poses[k - 1].t), py(score.position_errors[k - 1])},
             {px(poses[k].t), py(score.position_errors[k])}, {160, 60, 0}, 1, cv::LINE_AA);
  }
  cv::rectangle(image, {left, top}, {width - right, height - bottom}, {0, 0, 0}, 1);
  char text[200];
  for (int i = 0; i <= 4; ++i) {
    const double e = max_error * i / 4.0;
    std::snprintf(text, sizeof text, "%.2f", e);
    cv::putText(image, text, {10, py(e) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0});
  }
  std::snprintf(text, sizeof text, "%.0f s", t1 - t0);
  cv::putText(image, "0 s", {left, height - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0});
  cv::putText(image, text, {width - right - 60, height - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0});
  std::snprintf(text, sizeof text,
                "%s: position error [m] vs the reference (GMapping); strip: status (grey INIT, green OK, orange "
                "UNCERTAIN, red LOST)",
                title.c_str());
  cv::putText(image, text, {left, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0});
  if (!cv::imwrite(png_path, image)) {
    throw std::runtime_error("cannot write " + png_path);
  }
}

}  // namespace slamer

#include "tools/eval/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

namespace slamer {
namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, a, b);
  return text;
}

std::string accuracy_cell(const AccuracyStats& s, double value) {
  return s.scans == 0 ? "n/a" : format("%.2f %%", 100.0 * value);
}

// Non-finite numbers are JSON null.
nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json accuracy_json(const AccuracyStats& s) {
  if (s.scans == 0) {
    return nullptr;
  }
  return {{"scans", s.scans},          {"objects", s.objects},      {"mean", json_number(s.mean)},
          {"std", json_number(s.std)}, {"min", json_number(s.min)}, {"max", json_number(s.max)}};
}

}  // namespace

std::string render_table(const std::vector<NamedRun>& runs, const EvalOptions& options) {
  std::vector<std::pair<std::string, std::vector<std::string>>> rows;
  const auto add = [&](const std::string& label, auto cell) {
    std::vector<std::string> cells;
    for (const NamedRun& run : runs) {
      cells.push_back(cell(run.scores));
    }
    rows.emplace_back(label, cells);
  };
  const auto pose = [](auto f) {
    return [f](const RunScores& s) { return s.pose.samples == 0 ? std::string("n/a") : f(s.pose); };
  };
  add("Pose error [cm / deg]  Ave", pose([](const PoseErrorStats& p) {
        return format("%.2f / %.2f", 100.0 * p.position_mean, kDeg * p.heading_mean);
      }));
  add("                       Std", pose([](const PoseErrorStats& p) {
        return format("%.2f / %.2f", 100.0 * p.position_std, kDeg * p.heading_std);
      }));
  add("                       Max", pose([](const PoseErrorStats& p) {
        return format("%.2f / %.2f", 100.0 * p.position_max, kDeg * p.heading_max);
      }));
  add(format("Lost (> %.2f m) [%% of scans]", options.lost_threshold),
      pose([](const PoseErrorStats& p) { return format("%.2f", 100.0 * p.lost_fraction); }));
  add("Poses evaluated", pose([](const PoseErrorStats& p) { return std::to_string(p.samples); }));
  // Issue 9's bars (common/stats/status_honesty.hpp): the scans far off that say
  // UNCERTAIN or LOST from 2 s after the error passed 0.5 m, the close ones that say LOST.
  const auto honesty = [](auto f) {
    return [f](const RunScores& s) { return s.honesty ? f(*s.honesty) : std::string("n/a"); };
  };
  add("Status: > 0.5 m off, 2 s on, not OK", honesty([](const StatusHonesty& h) {
        return h.far_after_grace() == 0 ? std::string("none that far")
                                        : format("%.1f %% of %.0f", 100.0 * h.far_flagged_fraction(),
                                                 static_cast<double>(h.far_after_grace()));
      }));
  add("        < 0.2 m off, LOST / not OK [%]", honesty([](const StatusHonesty& h) {
        return format("%.2f / %.2f", 100.0 * h.close_lost_fraction(), 100.0 * h.close_not_ok_fraction());
      }));
  const std::pair<const char*, AccuracyStats RunScores::*> methods[] = {{"ER Acc (recognizer)", &RunScores::recognizer},
                                                                        {"Map-based ER Acc", &RunScores::map_based},
                                                                        {"SLAMER ER Acc", &RunScores::slamer}};
  for (const auto& method : methods) {
    // A copy, not a structured binding: clang before 16 cannot capture a binding in a lambda.
    const auto member = method.second;
    const std::string label = method.first;
    add(label + std::string(26 - std::min<std::size_t>(26, label.size()), ' ') + " Ave",
        [member](const RunScores& s) { return accuracy_cell(s.*member, (s.*member).mean); });
    add(std::string(27, ' ') + "Std",
        [member](const RunScores& s) { return accuracy_cell(s.*member, (s.*member).std); });
    add(std::string(27, ' ') + "Min",
        [member](const RunScores& s) { return accuracy_cell(s.*member, (s.*member).min); });
    add(std::string(27, ' ') + "Max",
        [member](const RunScores& s) { return accuracy_cell(s.*member, (s.*member).max); });
  }
  std::size_t label_width = 0;
  for (const auto& row : rows) {
    label_width = std::max(label_width, row.first.size());
  }
  std::vector<std::size_t> widths;
  for (const NamedRun& run : runs) {
    widths.push_back(std::max<std::size_t>(run.name.size(), 16));
  }
  std::ostringstream out;
  out << std::string(label_width, ' ');
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out << "  " << std::string(widths[i] - runs[i].name.size(), ' ') << runs[i].name;
  }
  out << "\n";
  for (const auto& [label, cells] : rows) {
    out << label << std::string(label_width - label.size(), ' ');
    for (std::size_t i = 0; i < cells.size(); ++i) {
      out << "  " << std::string(widths[i] - std::min(widths[i], cells[i].size()), ' ') << cells[i];
    }
    out << "\n";
  }
  return out.str();
}

std::string render_json(const std::vector<NamedRun>& runs, const EvalOptions& options) {
  nlohmann::json out{{"lost_threshold", json_number(options.lost_threshold)}, {"runs", nlohmann::json::array()}};
  for (const NamedRun& run : runs) {
    const RunScores& s = run.scores;
    const PoseErrorStats& p = s.pose;
    nlohmann::json pose = nullptr;
    if (p.samples > 0) {
      pose = {{"samples", p.samples},
              {"position_mean_m", json_number(p.position_mean)},
              {"position_std_m", json_number(p.position_std)},
              {"position_max_m", json_number(p.position_max)},
              {"heading_mean_rad", json_number(p.heading_mean)},
              {"heading_std_rad", json_number(p.heading_std)},
              {"heading_max_rad", json_number(p.heading_max)},
              {"lost_fraction", json_number(p.lost_fraction)}};
    }
    nlohmann::json honesty = nullptr;
    if (s.honesty) {
      const StatusHonesty& h = *s.honesty;
      honesty = {
          {"far_scans_after_2s", h.far_after_grace()},        {"far_flagged_after_2s", h.far_after_grace_flagged()},
          {"far_flagged_fraction", h.far_flagged_fraction()}, {"close_scans", h.close()},
          {"close_lost_fraction", h.close_lost_fraction()},   {"close_not_ok_fraction", h.close_not_ok_fraction()}};
    }
    out["runs"].push_back({{"name", run.name},
                           {"pose", pose},
                           {"status_honesty", honesty},
                           {"recognizer", accuracy_json(s.recognizer)},
                           {"map_based", accuracy_json(s.map_based)},
                           {"slamer", accuracy_json(s.slamer)}});
  }
  // Invalid UTF-8 in a run name (a file name) is replaced, not an exception.
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void write_error_plot(const std::vector<NamedRun>& runs, const std::string& png_path) {
  constexpr int kWidth = 1000;
  constexpr int kHeight = 420;
  constexpr int kLeft = 70;
  constexpr int kRight = 20;
  constexpr int kTop = 30;
  constexpr int kBottom = 50;
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  int64_t t0 = std::numeric_limits<int64_t>::max();
  int64_t t1 = std::numeric_limits<int64_t>::min();
  double max_error = 0.0;
  for (const NamedRun& run : runs) {
    for (const PoseError& e : run.scores.errors) {
      t0 = std::min(t0, e.utime);
      t1 = std::max(t1, e.utime);
      max_error = std::max(max_error, e.position);
    }
  }
  const double duration = t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 1.0;
  // The vertical range in cm: the first of 1, 2, 5, 10, 20, 50, ... above the largest error.
  double top_cm = 1.0;
  for (double decade = 1.0; top_cm < 100.0 * max_error; decade *= 10.0) {
    for (const double step : {1.0, 2.0, 5.0, 10.0}) {
      top_cm = step * decade;
      if (top_cm >= 100.0 * max_error) {
        break;
      }
    }
  }
  const auto to_px = [&](double seconds, double cm) {
    return cv::Point(kLeft + static_cast<int>(seconds / duration * (kWidth - kLeft - kRight)),
                     kHeight - kBottom - static_cast<int>(cm / top_cm * (kHeight - kTop - kBottom)));
  };
  const cv::Scalar grey(200, 200, 200);
  const cv::Scalar black(0, 0, 0);
  for (int i = 0; i <= 5; ++i) {
    const double cm = top_cm * i / 5.0;
    cv::line(image, to_px(0, cm), to_px(duration, cm), grey, 1);
    cv::putText(image, format("%.0f", cm), {5, to_px(0, cm).y + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, black, 1,
                cv::LINE_AA);
    const double s = duration * i / 5.0;
    cv::putText(image, format("%.0f", s), {to_px(s, 0).x - 10, kHeight - kBottom + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                black, 1, cv::LINE_AA);
  }
  cv::putText(image, "position error [cm]", {kLeft, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, black, 1, cv::LINE_AA);
  cv::putText(image, "time [s]", {kWidth / 2 - 30, kHeight - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.55, black, 1,
              cv::LINE_AA);
  const cv::Scalar colours[] = {{200, 80, 0}, {0, 0, 220}, {0, 150, 0}, {180, 0, 180}, {0, 140, 255}};
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const cv::Scalar colour = colours[r % 5];
    std::vector<cv::Point> points;
    for (const PoseError& e : runs[r].scores.errors) {
      points.push_back(to_px(static_cast<double>(e.utime - t0) * 1e-6, 100.0 * e.position));
    }
    if (points.size() > 1) {
      cv::polylines(image, points, false, colour, 1, cv::LINE_AA);
    }
    cv::putText(image, runs[r].name, {kWidth - 320, kTop + 20 + 20 * static_cast<int>(r)}, cv::FONT_HERSHEY_SIMPLEX,
                0.5, colour, 1, cv::LINE_AA);
  }
  if (!cv::imwrite(png_path, image)) {
    throw std::runtime_error("cannot write " + png_path);
  }
}

}  // namespace slamer

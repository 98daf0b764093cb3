// The real programs on a synthetic corrected CARMEN log of a room with a
// pillar (reference = the true path, odometry with a 2 % scale and heading
// bias, re-anchored as GMapping writes it, one malformed line):
// slamer-carmen2lcm, slamer-mapgen and slamer-bench with the real localizer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "common/geometry/se2.hpp"
#include "common/map/semantic_map.hpp"
#include "common/process/decode.hpp"
#include "common/process/event_log.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/odometry_t.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

std::vector<Segment> room() {
  const auto box = [](double x0, double y0, double x1, double y1) {
    return std::vector<Segment>{{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
  };
  std::vector<Segment> walls = box(0.0, 0.0, 8.0, 6.0);
  for (const Segment& s : box(3.0, 2.5, 4.0, 3.5)) {
    walls.push_back(s);
  }
  walls.push_back({{7.5, 0.0}, {7.5, 2.0}});  // a wall stub breaks the symmetry
  return walls;
}

double cast(const Pose2& laser, double angle, const std::vector<Segment>& walls) {
  const Eigen::Vector2d o(laser.x, laser.y);
  const Eigen::Vector2d d(std::cos(laser.theta + angle), std::sin(laser.theta + angle));
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : walls) {
    const Eigen::Vector2d e = b - a;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (std::abs(den) < 1e-12) {
      continue;
    }
    const Eigen::Vector2d w = a - o;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den;
    const double u = (w.x() * d.y() - w.y() * d.x()) / den;
    if (t > 0.0 && u >= 0.0 && u <= 1.0) {
      best = std::min(best, t);
    }
  }
  return best;
}

std::string pose_text(const Pose2& p) {
  char text[96];
  std::snprintf(text, sizeof text, "%.6f %.6f %.6f", p.x, p.y, p.theta);
  return text;
}

// Two loops around the pillar (4.5 x 2.2 m legs, 0.76 m corner radius): 150 scans, 0.1 s apart.
int write_log(const std::string& path) {
  const std::vector<Segment> walls = room();
  std::ofstream out(path);
  out << "PARAM robot_frontlaser_offset 0.0 synth 0\n";
  Pose2 truth{1.2, 1.0, 0.0};
  Pose2 raw{0.0, 0.0, 0.0};
  out << "ODOM " << pose_text(raw) << " 0 0 0 0.05 synth 0.05\n";
  const int scans = 150;
  for (int k = 0; k < scans; ++k) {
    const double t = 100.0 + 0.1 * k;
    out << "FLASER 180";
    for (int i = 0; i < 180; ++i) {
      const double r = cast(truth, -std::numbers::pi / 2 + i * std::numbers::pi / 180, walls);
      out << " " << (std::isfinite(r) && r < 40.0 ? r : 81.91);
    }
    out << " " << pose_text(truth) << " " << pose_text(truth) << " " << t << " synth " << t << "\n";
    if (k == 40) {
      out << "FLASER 180 1 2 3\n";  // malformed: reported with its line number, the rest imported
    }
    out << "ODOM " << pose_text(truth) << " 0 0 0 0 synth 0\n";
    // Straight legs of 28 and 14 steps, quarter turns of 12 steps between them.
    const int phase = k % 66;
    const bool straight = phase < 28 || (phase >= 40 && phase < 54);
    const Pose2 step = straight ? Pose2{0.16, 0.0, 0.0} : Pose2{0.1, 0.0, std::numbers::pi / 24};
    const Pose2 biased{step.x * 1.02, step.y, step.theta + 0.004};  // uncalibrated odometry
    out << "ODOM " << pose_text(compose(truth, biased)) << " 0 0 0 " << t + 0.09 << " synth 0\n";
    truth = compose(truth, step);
    raw = compose(raw, biased);
  }
  return scans;
}

TEST(DatasetTools, ImportMapAndBenchASyntheticCorrectedLog) {
  const std::string dir = (std::filesystem::temp_directory_path() / "slamer_dataset_tools_test").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string log = dir + "/synthetic-corrected.log";
  const int scans = write_log(log);

  test::ChildProcess convert(test::binary_path("slamer-carmen2lcm"), {log, dir + "/log.lcm"});
  ASSERT_EQ(convert.wait(60), 0) << convert.stderr_text();
  EXPECT_NE(convert.stderr_text().find("synthetic-corrected.log:124: FLASER"), std::string::npos)
      << convert.stderr_text();
  int lidar = 0;
  int odometry = 0;
  int ground_truth = 0;
  EventLogReader reader(dir + "/log.lcm");
  int64_t last = -1;
  while (const auto event = reader.next()) {
    ASSERT_GE(event->timestamp, last);
    last = event->timestamp;
    if (event->channel == "LIDAR") {
      laser_scan_t m;
      ASSERT_EQ(decode_message(event->data.data(), event->data.size(), &m), DecodeStatus::kOk);
      EXPECT_EQ(m.utime, event->timestamp);  // replays see the recorded timing
      EXPECT_EQ(m.sensor_utime, 100'000'000 + 100'000 * lidar);
      ++lidar;
    } else if (event->channel == "ODOMETRY") {
      odometry_t m;
      ASSERT_EQ(decode_message(event->data.data(), event->data.size(), &m), DecodeStatus::kOk);
      EXPECT_EQ(m.utime, event->timestamp);
      ++odometry;
    } else if (event->channel == "GROUND_TRUTH") {
      ++ground_truth;
    }
  }
  EXPECT_EQ(lidar, scans);
  EXPECT_EQ(ground_truth, scans);
  EXPECT_EQ(odometry, scans);

  test::ChildProcess mapgen(test::binary_path("slamer-mapgen"), {dir + "/log.lcm", dir + "/map"});
  ASSERT_EQ(mapgen.wait(60), 0) << mapgen.stderr_text();
  const SemanticMap map = load_semantic_map(dir + "/map/map.yaml");
  const auto occupied = [&](double x, double y) {
    const auto cell = map.geometry.cell_at({x, y});
    return cell && map.occupancy[map.geometry.index(cell->x, cell->y)] == Occupancy::kOccupied;
  };
  EXPECT_TRUE(occupied(2.99, 3.0) || occupied(3.01, 3.0));  // the pillar's face at x = 3
  EXPECT_FALSE(occupied(2.0, 2.0));

  test::ChildProcess bench(
      test::binary_path("slamer-bench"),
      {"--carmen", log, "--particles", "300", "--beams", "60", "--mode", "lfm", "--seed", "2", "--out", dir + "/bench",
       "--localizer-config", std::string(SLAMER_SOURCE_DIR) + "/config/localizer.yaml"});
  ASSERT_EQ(bench.wait(120), 0) << bench.stderr_text();
  std::istringstream poses(test::read_file(dir + "/bench/poses.txt"));
  std::string line;
  int lines = 0;
  while (std::getline(poses, line)) {
    double t = 0.0;
    double x = 0.0;
    double y = 0.0;
    double theta = 0.0;
    char status[16] = {};
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf %lf %15s", &t, &x, &y, &theta, status), 5) << line;
    EXPECT_NEAR(t, 100.0 + 0.1 * lines, 1e-6);  // the log's own time
    ++lines;
  }
  EXPECT_EQ(lines, scans);
  const auto summary = nlohmann::json::parse(test::read_file(dir + "/bench/summary.json"));
  EXPECT_EQ(summary["scans"].get<int>(), scans);
  EXPECT_EQ(summary["scans_without_pose"].get<int>(), 0);
  EXPECT_LT(summary["position_error_m"]["mean"].get<double>(), 0.10);  // tracks despite the 2 % bias
  EXPECT_EQ(summary["fraction_lost"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/bench/errors.png"));
  EXPECT_NE(test::read_file(dir + "/bench/localizer.yaml").find("beam_step: 3"), std::string::npos);

  // Another seed tracks too, so the two runs agree from the first scan; a
  // single run cannot agree with anything.
  test::ChildProcess other_seed(
      test::binary_path("slamer-bench"),
      {"--carmen", log, "--particles", "300", "--beams", "60", "--mode", "lfm", "--seed", "3", "--out", dir + "/bench3",
       "--localizer-config", std::string(SLAMER_SOURCE_DIR) + "/config/localizer.yaml"});
  ASSERT_EQ(other_seed.wait(120), 0) << other_seed.stderr_text();
  test::ChildProcess settle(test::binary_path("slamer-settle"),
                            {"--agree", "0.5", dir + "/bench/localized.lcm", dir + "/bench3/localized.lcm"});
  ASSERT_EQ(settle.wait(60), 0) << settle.stderr_text();
  EXPECT_NE(
      settle.stdout_text().find("the 2 runs agree within 0.50 m from scan 0 (0.0 s) of " + std::to_string(scans) + ";"),
      std::string::npos)
      << settle.stdout_text();
  test::ChildProcess alone(test::binary_path("slamer-settle"), {"--agree", "0.5", dir + "/bench/localized.lcm"});
  EXPECT_EQ(alone.wait(60), 2);
  EXPECT_NE(alone.stderr_text().find("--agree takes a distance > 0 [m] and two LOGs or more"), std::string::npos)
      << alone.stderr_text();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slamer

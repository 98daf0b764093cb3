// The real programs on a synthetic corrected CARMEN log of a room with a
// pillar (reference = the true path, odometry with a 2 % scale and heading
// bias, re-anchored as GMapping writes it, one malformed line):
// slamer-carmen2lcm, slamer-mapgen and slamer-bench with the real localizer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

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
       "--localizer-config", std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml")});
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
       "--localizer-config", std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml")});
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

  // Started by global localization: right within the first seconds, never OK while more than
  // 0.5 m off, OK by the end (late: only the wall stub tells the room from its half-turned twin,
  // so the status says UNCERTAIN, another place fits about as well, for most of the 15 s).
  test::ChildProcess global(
      test::binary_path("slamer-bench"),
      {"--carmen", log, "--particles", "1000", "--beams", "60", "--seed", "2", "--global", "--out", dir + "/global",
       "--localizer-config", std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml")});
  ASSERT_EQ(global.wait(120), 0) << global.stderr_text();
  const auto found = nlohmann::json::parse(test::read_file(dir + "/global/summary.json"));
  EXPECT_EQ(found["start"].get<std::string>(), "global localization");
  EXPECT_NE(found["localizer_command"].get<std::string>().find(" --global "), std::string::npos);
  EXPECT_EQ(found["localizer_command"].get<std::string>().find("--initial-pose"), std::string::npos);
  ASSERT_TRUE(found["right_from"]["scan"].is_number()) << found.dump();
  EXPECT_LT(found["right_from"]["scan"].get<int>(), 30) << found.dump();
  ASSERT_TRUE(found["right_from"]["ok_scan"].is_number()) << found.dump();
  const std::string global_poses = test::read_file(dir + "/global/poses.txt");
  EXPECT_EQ(global_poses.substr(global_poses.size() - 4), " OK\n");
  EXPECT_EQ(found["status_vs_error"]["OK"]["error_above_0.5m"].get<int>(), 0) << found.dump();
  EXPECT_NE(global.stderr_text().find("global localization: within 0.5 m to the end from scan"), std::string::npos)
      << global.stderr_text();

  // Kidnapped: carried 5.5 m and 90 deg unseen at scan 40 (4.0 s), 50 scans left out; the status
  // flags the far scans (the remaining 6 s are too short to relocalize in this room and its twin).
  test::ChildProcess kidnap(
      test::binary_path("slamer-bench"),
      {"--carmen", log, "--particles", "300", "--beams", "60", "--seed", "2", "--kidnap", "40", "90", "--out",
       dir + "/kidnap", "--localizer-config", std::string(SLAMER_SOURCE_DIR "/config/localizer.yaml")});
  ASSERT_EQ(kidnap.wait(120), 0) << kidnap.stderr_text();
  const auto carried = nlohmann::json::parse(test::read_file(dir + "/kidnap/summary.json"));
  EXPECT_EQ(carried["kidnap"]["from_scan"].get<int>(), 40);
  EXPECT_EQ(carried["kidnap"]["to_scan"].get<int>(), 90);
  EXPECT_EQ(carried["scans"].get<int>(), scans - 50);
  // poses.txt: one line per scan of the log, the carried ones repeating scan 39's line but for its time.
  std::vector<std::string> carried_lines;
  std::istringstream carried_poses(test::read_file(dir + "/kidnap/poses.txt"));
  for (std::string text; std::getline(carried_poses, text);) {
    carried_lines.push_back(text);
  }
  ASSERT_EQ(carried_lines.size(), static_cast<std::size_t>(scans));
  const auto after_time = [](const std::string& text) { return text.substr(text.find(' ')); };
  EXPECT_EQ(after_time(carried_lines[40]), after_time(carried_lines[39]));
  EXPECT_EQ(after_time(carried_lines[89]), after_time(carried_lines[39]));
  EXPECT_NE(carried_lines[89].substr(0, carried_lines[89].find(' ')),
            carried_lines[39].substr(0, carried_lines[39].find(' ')));
  EXPECT_GT(carried["fraction_lost"].get<double>(), 0.3);
  EXPECT_GT(carried["status_honesty"]["far_scans_after_2s"].get<int>(), 20);
  EXPECT_GE(carried["status_honesty"]["far_flagged_fraction"].get<double>(), 0.9);
  EXPECT_NE(kidnap.stderr_text().find("kidnap: scans 40-89 left out; at scan 40 (4.0 s into the run) the robot was "
                                      "carried 5.5 m and 90 deg unseen"),
            std::string::npos)
      << kidnap.stderr_text();
  EXPECT_NE(kidnap.stderr_text().find("after the kidnap: within 0.5 m"), std::string::npos) << kidnap.stderr_text();
  test::ChildProcess bad_kidnap(test::binary_path("slamer-bench"),
                                {"--carmen", log, "--kidnap", "90", "40", "--out", dir + "/bad"});
  EXPECT_EQ(bad_kidnap.wait(60), 2);
  EXPECT_NE(bad_kidnap.stderr_text().find("--kidnap FROM TO needs scan numbers 0 < FROM < TO < 150"), std::string::npos)
      << bad_kidnap.stderr_text();
  test::ChildProcess half_scan(test::binary_path("slamer-bench"),
                               {"--carmen", log, "--kidnap", "40.5", "90", "--out", dir + "/bad"});
  EXPECT_EQ(half_scan.wait(60), 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slamer

// The raw odometry rebuilt from a corrected CARMEN log's re-anchored ODOM
// lines: exactly on a synthetic log, within noise of the reference on the
// shared logs (which must drift as real odometry does), and the time rules.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "tools/datasets/dataset_import.hpp"

namespace slamer {
namespace {

std::string pose_text(const Pose2& p) {
  char text[96];
  std::snprintf(text, sizeof text, "%.9f %.9f %.9f", p.x, p.y, p.theta);
  return text;
}

// A corrected log as GMapping writes it: per scan the reference pose, then
// ODOM lines re-anchored to it (the first equal to it, with time 0).
struct SyntheticLog {
  std::vector<Pose2> reference;
  std::vector<Pose2> raw;  // the odometry the log hides
  std::string path;
};

SyntheticLog write_synthetic_log(bool frozen_clock) {
  SyntheticLog log;
  // One file per test: ctest runs the two tests that write it side by side.
  log.path = (std::filesystem::temp_directory_path() /
              ("slamer_synthetic_corrected_" + std::string(frozen_clock ? "frozen" : "running") + ".log"))
                 .string();
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  Pose2 ref{1.0, 2.0, 0.3};
  Pose2 raw{-5.0, 3.0, -1.0};
  std::ofstream out(log.path);
  out << "ODOM " << pose_text(raw) << " 0 0 0 0.5 synth 0.5\n";
  for (int k = 0; k < 50; ++k) {
    log.reference.push_back(ref);
    log.raw.push_back(raw);
    // csail's clock: 6 printed digits, one value for most scans, then a step of 10^4 s.
    const double t = frozen_clock ? (k < 40 ? 1.13486e9 : 1.13487e9) : 10.0 + 0.25 * k;
    out << "FLASER 3 1 2 3 " << pose_text(ref) << " " << pose_text(ref) << " " << t << " synth " << t << "\n";
    out << "ODOM " << pose_text(ref) << " 0 0 0 0 synth 0\n";
    const Pose2 step{0.3 + noise(rng), noise(rng), 0.1 + noise(rng)};
    for (int j = 1; j <= 3; ++j) {  // three ODOM lines along the raw step
      const Pose2 part = interpolate(Pose2{}, step, j / 3.0);
      out << "ODOM " << pose_text(compose(ref, part)) << " 0 0 0 " << t + 0.05 * j << " synth 0\n";
    }
    raw = compose(raw, step);
    ref = compose(ref, Pose2{0.31, 0.01, 0.09});  // the "corrected" path differs from the raw one
  }
  return log;
}

TEST(DatasetImport, RebuildsTheHiddenRawOdometryExactly) {
  const SyntheticLog truth = write_synthetic_log(false);
  const ImportedLog log = import_dataset(truth.path, {});
  ASSERT_TRUE(log.corrected);
  ASSERT_EQ(log.scans.size(), truth.reference.size());
  EXPECT_EQ(log.reanchor_mismatches, 0);
  for (std::size_t k = 0; k < truth.raw.size(); ++k) {
    EXPECT_NEAR(log.scan_odometry[k].x, truth.raw[k].x, 1e-6) << k;
    EXPECT_NEAR(log.scan_odometry[k].y, truth.raw[k].y, 1e-6) << k;
    EXPECT_NEAR(angle_diff(log.scan_odometry[k].theta, truth.raw[k].theta), 0.0, 1e-6) << k;
    EXPECT_NEAR(log.reference[k].x, truth.reference[k].x, 1e-9);
    EXPECT_EQ(log.scans[k].sensor_utime, log.scans[k].utime);  // the log's clock is fine here
  }
  // Two intermediate poses per interval (the anchor and the last are the scans' own).
  EXPECT_EQ(log.odometry.size(), truth.raw.size() + 2 * (truth.raw.size() - 1));
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    ASSERT_GT(log.odometry[i].utime, log.odometry[i - 1].utime);
    EXPECT_TRUE(std::isfinite(log.odometry[i].v) && std::isfinite(log.odometry[i].omega));
  }
  EXPECT_NEAR(log.odometry[1].v, 0.1 / (0.25 / 3), 0.1 * 0.25 / 3 * 40);  // ~0.1 m per 83 ms
  std::filesystem::remove(truth.path);
}

TEST(DatasetImport, FrozenLogClockGetsStrictlyIncreasingUtimes) {
  const SyntheticLog truth = write_synthetic_log(true);  // scans at 1.13486e9, then 1.13487e9, as csail
  const ImportedLog log = import_dataset(truth.path, {});
  ASSERT_EQ(log.scans.size(), truth.reference.size());
  EXPECT_EQ(log.retimed, static_cast<int64_t>(truth.reference.size()) - 1);
  for (std::size_t k = 1; k < log.scans.size(); ++k) {
    // The nominal 100 ms, across the printed clock's step too (not a gap of 10^4 s).
    EXPECT_EQ(log.scans[k].utime - log.scans[k - 1].utime, 100'000) << k;
    EXPECT_EQ(log.scans[k].sensor_utime, k < 40 ? 1'134'860'000'000'000 : 1'134'870'000'000'000);  // the log's own
  }
  std::filesystem::remove(truth.path);
}

// The shared logs: the rebuilt increments match the reference within noise,
// and dead reckoning drifts away from it as real odometry does.
TEST(DatasetImport, SharedLogsOdometryDrift) {
  const std::string dir = std::string(SLAMER_SOURCE_DIR "/../shared/datasets/ple_carmen_corrected/");
  if (!std::filesystem::exists(dir)) {
    GTEST_SKIP() << "../shared/datasets/ple_carmen_corrected is absent";
  }
  struct Expected {
    const char* name;
    double step_position;     // [m] bound on the mean increment difference (measured + margin)
    double step_heading_deg;  // the same for the heading
  };
  // csail is sub-sampled to 94 cm steps with fast turns: its increments differ most.
  for (const Expected& e :
       {Expected{"aces", 0.08, 2.5}, Expected{"csail", 0.13, 7.5}, Expected{"freiburg-079", 0.05, 1.5}}) {
    const char* name = e.name;
    const ImportedLog log = import_dataset(dir + name + "-corrected.log.gz", {});
    ASSERT_TRUE(log.corrected) << name;
    ASSERT_GT(log.scans.size(), 400u) << name;
    EXPECT_EQ(log.reanchor_mismatches, 0) << name;
    const OdometryDrift d = odometry_drift(log);
    std::printf(
        "%s: %zu scans, %.0f m of path; per step %.1f cm / %.2f deg from the reference; heading drift "
        "%.2f deg per metre; dead reckoning %.1f m off at the end, %.1f m at most\n",
        name, log.scans.size(), d.path_length, d.step_position_error * 100, d.step_heading_error_deg,
        d.heading_deg_per_m, d.final_position_error, d.max_position_error);
    EXPECT_LT(d.step_position_error, e.step_position) << name;  // each increment close to the reference's
    EXPECT_LT(d.step_heading_error_deg, e.step_heading_deg) << name;
    EXPECT_GT(d.heading_deg_per_m, 1.0) << name;  // yet it drifts as real odometry does
    EXPECT_LT(d.heading_deg_per_m, 30.0) << name;
    EXPECT_GT(d.max_position_error, 1.0) << name;
  }
}

}  // namespace
}  // namespace slamer

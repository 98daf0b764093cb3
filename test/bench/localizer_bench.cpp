// Localizer update speed per scan (prediction + LFM over the beams + the
// SLAMER term + posterior + resampling when due) on the paper-like world,
// from 100 to 5000 particles and at several beam counts.
//   build/bin/localizer_bench
#include <benchmark/benchmark.h>

#include <cmath>

#include "localizer/local_match.hpp"
#include "localizer/particle_filter.hpp"
#include "localizer/scan_fit.hpp"
#include "recognizer/line_recognizer.hpp"
#include "tools/sim/world.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;

struct Fixture {
  WorldOptions world_options = load_options<WorldOptions>(kSource + "/config/worlds/paper_indoor.yaml");
  RobotOptions robot = load_options<RobotOptions>(world_options.robot_path);
  SemanticMap map = load_semantic_map(world_options.map_path);
  TrueWorld world{map, world_options, "paper_indoor"};

  LaserScan scan(int beams, const Pose2& pose) const {
    LaserScan s;
    s.angle_min = robot.lidar.angle_min;
    s.angle_increment = (robot.lidar.angle_max - robot.lidar.angle_min) / (beams - 1);
    s.range_min = static_cast<float>(robot.lidar.range_min);
    s.range_max = static_cast<float>(robot.lidar.range_max);
    std::mt19937 rng(1);
    const Pose2 sensor = compose(pose, robot.lidar.mount);
    for (int i = 0; i < beams; ++i) {
      const double r =
          world.cast({sensor.x, sensor.y}, sensor.theta + s.angle(static_cast<std::size_t>(i)), 31.0, 0.0, rng);
      s.ranges.push_back(r <= 30.0 ? static_cast<float>(r) : std::numeric_limits<float>::infinity());
    }
    return s;
  }

  // A scan's end points in the sensor frame, in cells (ScanPoints).
  ScanPoints points(const LaserScan& scan) const {
    ScanPoints p;
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      if (scan.ranges[i] < scan.range_max) {
        p.x.push_back(static_cast<float>(scan.ranges[i] * std::cos(scan.angle(i)) / map.geometry.resolution));
        p.y.push_back(static_cast<float>(scan.ranges[i] * std::sin(scan.angle(i)) / map.geometry.resolution));
      }
    }
    return p;
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void run(benchmark::State& state, int particles, int beams, LocalizerMode mode, bool robust = true) {
  const Fixture& f = fixture();
  LocalizerOptions options;
  if (!robust) {  // issue 9's additions off: fixed motion noise, no odometry correction, no recovery
    options.motion.noise_gain_max = 1.0;
    options.motion.odometry_correction_memory = 0.0;
    options.recovery.candidates = 0;
    options.recovery.local.below = 0.0;
  }
  options.mode = mode;
  options.particles = particles;
  ParticleFilter filter(f.map, options, f.robot.lidar.mount);
  const Pose2 pose{20.0, 8.25, 0.0};  // mid-corridor, doors on both sides
  filter.initialize(pose, {0.05, 0.05, 0.02});
  const LaserScan scan = f.scan(beams, pose);
  const LineObjectSet objects = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  for (auto _ : state) {
    filter.predict({0.0, 0.0, 0.0}, {0.02, 0.0, 0.0}, 0.025);
    benchmark::DoNotOptimize(filter.update(scan, &objects));
  }
  state.counters["beam_evaluations_per_s"] =
      benchmark::Counter(static_cast<double>(particles) * beams, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["objects"] = static_cast<double>(objects.objects.size());
}

void BM_SlamerParticles(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), 1081, LocalizerMode::kSlamer);
}
BENCHMARK(BM_SlamerParticles)->Arg(100)->Arg(500)->Arg(1000)->Arg(2000)->Arg(5000)->Unit(benchmark::kMillisecond);

void BM_SlamerBeams(benchmark::State& state) {
  run(state, 500, static_cast<int>(state.range(0)), LocalizerMode::kSlamer);
}
BENCHMARK(BM_SlamerBeams)->Arg(271)->Arg(541)->Arg(1081)->Arg(2161)->Unit(benchmark::kMillisecond);

void BM_LfmParticles(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), 1081, LocalizerMode::kLfm);
}
BENCHMARK(BM_LfmParticles)->Arg(500)->Unit(benchmark::kMillisecond);

// Issue 9: what the robustness steps cost. Off = fixed noise, no correction, no recovery,
// no local scan match (the scan fit for the status is always computed).
void BM_LfmRobustOff(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), 1081, LocalizerMode::kLfm, false);
}
BENCHMARK(BM_LfmRobustOff)->Arg(500)->Unit(benchmark::kMillisecond);

// The scan fit at one pose (the status evidence), every beam.
void BM_ScanFit(benchmark::State& state) {
  const Fixture& f = fixture();
  const DistanceField obstacles = obstacle_distance_field(f.map, 1.2);
  const Pose2 pose{20.0, 8.25, 0.0};
  const LaserScan scan = f.scan(1081, pose);
  const ScanPoints points = f.points(scan);
  const Pose2 sensor = sensor_in_cells(f.map.geometry, pose, f.robot.lidar.mount);
  for (auto _ : state) {
    benchmark::DoNotOptimize(scan_fit(obstacles, points, sensor, 0.1));
  }
}
BENCHMARK(BM_ScanFit)->Unit(benchmark::kMicrosecond);

// One match_locally of a 1081-beam scan taken at (20, 8.25, 0), every beam's
// end point given, from `predicted`, on a field kept as the filter keeps it.
void match_from(benchmark::State& state, const LocalMatchWindow& window, const Pose2& predicted) {
  const Fixture& f = fixture();
  const LocalizerOptions options;
  const LikelihoodField field(std::make_shared<const DistanceField>(obstacle_distance_field(f.map, 1.2)), options.lfm,
                              ParticleFilter::kDenseFieldCellsMax);
  const ScanPoints points = f.points(f.scan(1081, {20.0, 8.25, 0.0}));
  for (auto _ : state) {
    benchmark::DoNotOptimize(match_locally(field, points, f.robot.lidar.mount, predicted, window));
  }
}

// What a scan costs on top when the prediction fits it poorly: the shipped
// window, 0.5 m and 0.5 rad, from a prediction 0.3 m and 0.2 rad off.
void BM_LocalMatch(benchmark::State& state) {
  const LocalizerOptions options;
  match_from(state, {options.recovery.local.shift, options.recovery.local.turn}, {20.3, 8.25, 0.2});
}
BENCHMARK(BM_LocalMatch)->Unit(benchmark::kMillisecond);

// The adopted place's refinement (ParticleFilter::refined_place, once an
// adoption): 0.3 m and 0.15 rad at 5 cm and 0.025 rad, 180 beams, from a
// place 0.1 m and 0.05 rad off.
void BM_RefineAdoptedPlace(benchmark::State& state) {
  match_from(state, {0.3, 0.15, 0.05, 0.025, 180}, {20.1, 8.25, 0.05});
}
BENCHMARK(BM_RefineAdoptedPlace)->Unit(benchmark::kMillisecond);

// The beams' log-likelihood alone (LikelihoodField::sum_placed) at 500 poses
// around (20, 8.25, 0), 1081 beams, on a field kept as the filter keeps it:
// Arg 0 the portable code, 1 the best this machine has (AVX2 on x86-64).
void BM_SumPlaced(benchmark::State& state) {
  const Fixture& f = fixture();
  const LocalizerOptions options;
  const LikelihoodField field(
      std::make_shared<const DistanceField>(obstacle_distance_field(f.map, 1.2)), options.lfm,
      ParticleFilter::kDenseFieldCellsMax,
      state.range(0) == 0 ? LikelihoodField::Vectorization::kPortable : LikelihoodField::Vectorization::kBest);
  const ScanPoints points = f.points(f.scan(1081, {20.0, 8.25, 0.0}));
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Pose2> sensors;
  for (int i = 0; i < 500; ++i) {
    const Pose2 pose{20.0 + 0.05 * noise(rng), 8.25 + 0.05 * noise(rng), 0.02 * noise(rng)};
    sensors.push_back(sensor_in_cells(f.map.geometry, pose, f.robot.lidar.mount));
  }
  for (auto _ : state) {
    double sum = 0.0;
    for (const Pose2& p : sensors) {
      sum += field.sum_placed(points.x.data(), points.y.data(), points.x.size(), static_cast<float>(std::cos(p.theta)),
                              static_cast<float>(std::sin(p.theta)), static_cast<float>(p.x), static_cast<float>(p.y));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["beam_evaluations_per_s"] =
      benchmark::Counter(500.0 * static_cast<double>(points.x.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["avx2"] = field.sums_with_avx2() ? 1.0 : 0.0;
}
BENCHMARK(BM_SumPlaced)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One global proposal's climb (ParticleFilter::inject, climb_locally): steps of
// 0.1 m and 0.05 rad halving three times, 48 beams, from a proposal 0.15 m and
// 0.05 rad off the pose the scan was taken at.
void BM_ClimbProposal(benchmark::State& state) {
  const Fixture& f = fixture();
  const LocalizerOptions options;
  const LikelihoodField field(std::make_shared<const DistanceField>(obstacle_distance_field(f.map, 1.2)), options.lfm);
  const ScanPoints points = f.points(f.scan(1081, {20.0, 8.25, 0.0}));
  for (auto _ : state) {
    benchmark::DoNotOptimize(climb_locally(field, points, f.robot.lidar.mount, {20.15, 8.25, 0.05}, 0.1, 0.05, 48));
  }
}
BENCHMARK(BM_ClimbProposal)->Unit(benchmark::kMicrosecond);

// A SLAMER filter with the shipped defaults and the scan (and its objects) of one place of the map.
struct SlamerAtOnePlace {
  LocalizerOptions options;
  ParticleFilter filter{fixture().map, options, fixture().robot.lidar.mount};
  LaserScan scan = fixture().scan(1081, {20.0, 8.25, 0.0});
  LineObjectSet objects = LineRecognizer{RecognizerOptions{}}.recognize(scan);
};

// One scan of a globally localizing SLAMER filter, 500 particles x 1081 beams:
// 2000 global proposals scored and 50 injected, each climbed, before the usual update.
void BM_SlamerRecovering(benchmark::State& state) {
  SlamerAtOnePlace one;
  ParticleFilter& filter = one.filter;
  const LaserScan& scan = one.scan;
  const LineObjectSet& objects = one.objects;
  filter.initialize_global();
  int injected = 0;
  for (auto _ : state) {
    const UpdateResult r = filter.update(scan, &objects);
    injected += r.injected;
    if (r.injected == 0) {
      state.PauseTiming();
      filter.initialize_global();  // found it: lose it again
      state.ResumeTiming();
    }
  }
  state.counters["injected_per_scan"] = benchmark::Counter(injected, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SlamerRecovering)->Unit(benchmark::kMillisecond);

// One scan of a LOST SLAMER filter with a cloud to keep (500 particles x 1081
// beams): 2000 global proposals scored, 10 of them joining the 50 challengers,
// which are weighted beside the 500 (particle_filter_challengers.cpp). The
// scans' time stands still, so the challengers never take the cloud.
void BM_SlamerLostCompeting(benchmark::State& state) {
  SlamerAtOnePlace one;
  ParticleFilter& filter = one.filter;
  const LaserScan& scan = one.scan;
  const LineObjectSet& objects = one.objects;
  filter.initialize({5.0, 5.0, 1.0}, {0.02, 0.02, 0.01});  // confidently somewhere else
  for (int k = 0; k < one.options.status.lost_after + 1; ++k) {
    filter.update(scan, &objects);
  }
  int competing = 0;
  for (auto _ : state) {
    const UpdateResult r = filter.update(scan, &objects);
    competing += r.estimate.status == LocalizerStatus::kLost && r.injected > 0;
  }
  state.counters["competing_fraction"] = benchmark::Counter(competing, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SlamerLostCompeting)->Unit(benchmark::kMillisecond);

void BM_SlfmParticles(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), 1081, LocalizerMode::kSlfm);
}
BENCHMARK(BM_SlfmParticles)->Arg(500)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamer

BENCHMARK_MAIN();

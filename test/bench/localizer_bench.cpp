// Localizer update speed per scan (prediction + LFM over the beams + the
// SLAMER term + posterior + resampling when due) on the paper-like world,
// from 100 to 5000 particles and at several beam counts.
//   build/bin/localizer_bench
#include <benchmark/benchmark.h>

#include "localizer/particle_filter.hpp"
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
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void run(benchmark::State& state, int particles, int beams, LocalizerMode mode) {
  const Fixture& f = fixture();
  LocalizerOptions options;
  options.mode = mode;
  options.particles = particles;
  ParticleFilter filter(f.map, options, f.robot.lidar.mount);
  const Pose2 pose{20.0, 8.25, 0.0};  // mid-corridor, doors on both sides
  filter.initialize(pose, {0.05, 0.05, 0.02});
  const LaserScan scan = f.scan(beams, pose);
  const LineObjectSet objects = LineRecognizer{RecognizerOptions{}}.recognize(scan);
  for (auto _ : state) {
    filter.predict({0.0, 0.0, 0.0}, {0.02, 0.0, 0.0});
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

void BM_SlfmParticles(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), 1081, LocalizerMode::kSlfm);
}
BENCHMARK(BM_SlfmParticles)->Arg(500)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamer

BENCHMARK_MAIN();

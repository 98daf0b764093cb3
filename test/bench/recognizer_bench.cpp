// Recognizer speed per scan (median and p99 over every scan recognized) on
// scans simulated in the bundled paper-like world at several beam counts,
// and on the real datasets in ../shared/datasets when they are there.
//   build/bin/recognizer_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>

#include "recognizer/line_recognizer.hpp"
#include "tools/datasets/dataset_scans.hpp"
#include "tools/sim/simulator.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;

class ScanCollector : public SimulatorSink {
 public:
  void on_scan(const LaserScan& scan, int64_t) override {
    if (count_++ % 8 == 0) {  // every 0.2 s of the drive
      scans.push_back(scan);
    }
  }
  void on_encoders(const EncoderSample&) override {}
  void on_odometry(const OdometrySample&) override {}
  void on_ground_truth(const GroundTruthSample&) override {}
  std::vector<LaserScan> scans;

 private:
  int count_ = 0;
};

// Scans of the first 120 s of the paper-like world's drive, with `beams` beams over 270 deg.
const std::vector<LaserScan>& simulated_scans(int beams) {
  static std::map<int, std::vector<LaserScan>> cache;
  auto it = cache.find(beams);
  if (it != cache.end()) {
    return it->second;
  }
  const std::string world_file = kSource + "/config/worlds/paper_indoor.yaml";
  const auto world_options = load_options<WorldOptions>(world_file);
  auto robot = load_options<RobotOptions>(world_options.robot_path);
  robot.lidar.beams = beams;
  robot.lidar.steps_per_revolution = std::max(1440, beams * 4 / 3 + 1);
  const TrueWorld world(load_semantic_map(world_options.map_path), world_options, world_file);
  SimOptions options;
  options.max_duration = 120.0;
  Simulator sim(world, world_options, robot, options, 1);
  ScanCollector collector;
  while (sim.step(collector)) {
  }
  return cache[beams] = std::move(collector.scans);
}

void run(benchmark::State& state, const std::vector<LaserScan>& scans) {
  if (scans.empty()) {
    state.SkipWithError("no scans (dataset missing?)");
    return;
  }
  const LineRecognizer recognizer{RecognizerOptions{}};
  std::vector<double> times;
  std::size_t objects = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const LaserScan& scan = scans[next++ % scans.size()];
    const auto start = std::chrono::steady_clock::now();
    const LineObjectSet result = recognizer.recognize(scan);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    objects += result.objects.size();
    benchmark::DoNotOptimize(result);
  }
  std::sort(times.begin(), times.end());
  state.counters["median_ms"] = times[times.size() / 2];
  state.counters["p99_ms"] = times[std::min(times.size() - 1, times.size() * 99 / 100)];
  state.counters["objects_per_scan"] = static_cast<double>(objects) / static_cast<double>(times.size());
  state.counters["beams"] = static_cast<double>(scans.front().ranges.size());
}

void BM_RecognizeSimulated(benchmark::State& state) {
  run(state, simulated_scans(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_RecognizeSimulated)->Arg(271)->Arg(541)->Arg(1081)->Arg(2161)->Unit(benchmark::kMillisecond);

void BM_RecognizeDataset(benchmark::State& state, const std::string& file, DatasetFormat format) {
  const std::string path = kSource + "/../shared/datasets/" + file;
  static std::map<std::string, std::vector<LaserScan>> cache;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("missing " + path).c_str());
    return;
  }
  if (cache.count(path) == 0) {
    cache[path] = read_dataset(path, format, 2000).scans;
  }
  run(state, cache[path]);
}
BENCHMARK_CAPTURE(BM_RecognizeDataset, carmen_aces, "ple_carmen_corrected/aces-corrected.log.gz",
                  DatasetFormat::kCarmen)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecognizeDataset, carmen_fr079, "ple_carmen_corrected/freiburg-079-corrected.log.gz",
                  DatasetFormat::kCarmen)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecognizeDataset, cmu_wean, "cmu_wean_16831/robotdata1.log.gz", DatasetFormat::kCmu)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RecognizeDataset, mines_urg04, "breezyslam_mines/exp1.dat", DatasetFormat::kMines)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamer

BENCHMARK_MAIN();

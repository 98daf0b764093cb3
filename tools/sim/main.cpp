// slamer-sim: the simulated i-Cart mini in a semantic world, live on LCM or
// straight into an LCM log file.
#include <unistd.h>

#include <cstdio>
#include <functional>
#include <iostream>

#include "common/process/convert.hpp"
#include "common/process/lcm_bus.hpp"
#include "common/process/log.hpp"
#include "common/process/log_bus.hpp"
#include "common/process/process_main.hpp"
#include "tools/sim/sim_config.hpp"

namespace slamer {
namespace {

// Encodes each output and hands it on with the time a device would deliver it.
class MessageSink : public SimulatorSink {
 public:
  using Emit = std::function<void(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t utime)>;
  MessageSink(const SimChannels& channels, Emit emit) : channels_(channels), emit_(std::move(emit)) {}

  void on_scan(const LaserScan& scan, int64_t publish_utime) override {
    send(channels_.lidar, to_message(scan), publish_utime);
    ++scans_;
  }
  void on_encoders(const EncoderSample& s) override {
    send(channels_.wheel_encoders, make_wheel_encoders(s.utime, s.seq, "sim", s.left, s.right), s.utime);
  }
  void on_odometry(const OdometrySample& s) override {
    send(channels_.odometry, make_odometry(s.utime, s.seq, s.pose, s.v, s.omega), s.utime);
  }
  void on_ground_truth(const GroundTruthSample& s) override {
    send(channels_.ground_truth, make_exact_pose(s.utime, s.pose), s.publish_utime);
  }
  int64_t scans() const { return scans_; }

 private:
  template <class Msg>
  void send(const std::string& channel, const Msg& msg, int64_t utime) {
    std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    emit_(channel, bytes, utime);
  }

  SimChannels channels_;
  Emit emit_;
  int64_t scans_ = 0;
};

// Steps the simulation in bus time (at `speed` times real time when live; as
// fast as the CPU allows into a log) until the path is done.
int run(Simulator& sim, const SimProcessConfig& config, Bus& bus, double speed) {
  MessageSink sink(config.channels, [&](const std::string& channel, const std::vector<uint8_t>& bytes, int64_t t) {
    bus.publish_raw(channel, bytes, t);
  });
  for (const std::string& channel : {config.channels.lidar, config.channels.wheel_encoders, config.channels.odometry,
                                     config.channels.ground_truth}) {
    bus.advertise(channel);
  }
  const int64_t start = bus.now();
  const bool terminal = !bus.is_live() && isatty(STDERR_FILENO) != 0;
  double next_report = 0.0;
  bool finished = false;
  bus.every(config.sim.step / speed, [&] {
    // Catch up with the bus clock: every step whose time has come.
    const double target = static_cast<double>(bus.now() - start) * 1e-6 * speed;
    while (!finished && sim.time() < target) {
      finished = !sim.step(sink);
    }
    if (terminal && sim.time() >= next_report) {
      std::fprintf(stderr, "\rslamer-sim: %7.1f s simulated, path %3.0f%% done", sim.time(), 100.0 * sim.progress());
      next_report += 5.0;
    }
    if (finished) {
      bus.log_info((terminal ? "\n" : "") + std::string("path finished after ") + std::to_string(sim.time()) + " s, " +
                   std::to_string(sink.scans()) + " scans");
      bus.stop();
    }
  });
  return bus.run();
}

}  // namespace
}  // namespace slamer

int main(int argc, char** argv) {
  return slamer::process_main(
      argc, argv, "slamer-sim",
      "Simulates the i-Cart mini driving a world's scripted path: LIDAR, WHEEL_ENCODERS, ODOMETRY and\n"
      "GROUND_TRUTH, live on LCM (at --speed times real time) or into an LCM log (--out), the same for\n"
      "the same seed.",
      [](slamer::CommandLine& cli) {
        cli.add_option("world", "FILE", "world file (config/worlds/*.yaml)");
        cli.add_option("seed", "N", "random seed", "1");
        cli.add_option("out", "FILE", "write an LCM log instead of publishing live");
        cli.add_option("speed", "X", "live mode: simulated seconds per wall-clock second", "1");
        cli.add_option("laps", "N", "drive the world's path N times over (for long runs)", "1");
      },
      [](const slamer::CommandLine& cli) {
        if (!cli.has("world")) {
          throw slamer::CommandLineError("--world FILE is required");
        }
        auto config = slamer::load_config<slamer::SimProcessConfig>(cli);
        const int64_t seed = cli.get_int("seed");
        const double speed = cli.get_double("speed");
        const int64_t laps = cli.get_int("laps");
        if (seed < 0 || !(speed > 0.0) || laps < 1 || laps > 1000) {
          throw slamer::CommandLineError("--seed must be >= 0, --speed > 0 and --laps in [1, 1000]");
        }
        const std::string world_file = cli.get("world");
        auto world_options = slamer::load_options<slamer::WorldOptions>(world_file);
        const std::vector<slamer::PathStep> lap = world_options.path;
        for (int64_t i = 1; i < laps; ++i) {
          world_options.path.insert(world_options.path.end(), lap.begin(), lap.end());
        }
        const auto robot = slamer::load_options<slamer::RobotOptions>(world_options.robot_path);
        slamer::SemanticMap map = slamer::load_semantic_map(world_options.map_path);
        for (const std::string& warning : map.warnings) {
          slamer::log_line("slamer-sim", slamer::LogLevel::kWarning, warning);
        }
        const slamer::TrueWorld world(std::move(map), world_options, world_file);
        std::unique_ptr<slamer::Bus> bus;
        if (cli.has("out")) {  // a log of its own: the clock starts at the config's start_utime
          bus = std::make_unique<slamer::LogBus>("slamer-sim", cli.get("out"), config.sim.start_utime, config.process);
        } else {
          bus = std::make_unique<slamer::LcmBus>("slamer-sim", cli.get("lcm-url"), config.process);
          config.sim.start_utime = bus->now();
        }
        slamer::Simulator sim(world, world_options, robot, config.sim, static_cast<uint64_t>(seed));
        return slamer::run(sim, config, *bus, speed);
      });
}

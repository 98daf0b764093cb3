// The programs' one wiring (localizer_process, recognizer_process) on the
// in-memory bus and on the replay bus: the simulated small world's sensor
// messages give the same POSE stream, scan for scan, whichever bus carries them.
#include <gtest/gtest.h>

#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>

#include "common/process/convert.hpp"
#include "common/process/event_log.hpp"
#include "common/process/log_bus.hpp"
#include "common/process/memory_bus.hpp"
#include "localizer/localizer_process.hpp"
#include "recognizer/recognizer_process.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/localizer/small_world.hpp"
#include "test/support/pose_matchers.hpp"
#include "tools/sim/simulator.hpp"

namespace slamer {
namespace {

struct Event {
  std::string channel;
  std::vector<uint8_t> bytes;
  int64_t utime;
};

// The first `scans` scans of the small world's drive with their odometry and truth.
class Recorder : public SimulatorSink {
 public:
  explicit Recorder(std::vector<Event>* events) : events_(events) {}
  void on_scan(const LaserScan& scan, int64_t publish_utime) override {
    add("LIDAR", to_message(scan), publish_utime);
    ++scans;
  }
  void on_encoders(const EncoderSample&) override {}
  void on_odometry(const OdometrySample& s) override {
    add("ODOMETRY", make_odometry(s.utime, s.seq, s.pose, s.v, s.omega), s.utime);
  }
  void on_ground_truth(const GroundTruthSample& s) override {
    add("GROUND_TRUTH", make_exact_pose(s.utime, s.pose), s.publish_utime);
  }
  int scans = 0;

 private:
  template <class Msg>
  void add(const std::string& channel, const Msg& msg, int64_t utime) {
    std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    events_->push_back({channel, std::move(bytes), utime});
  }
  std::vector<Event>* events_;
};

std::vector<Event> simulate(const SmallWorld& w, int scans) {
  std::vector<Event> events;
  Recorder recorder(&events);
  SimOptions options;
  options.start_utime = 1'700'000'000'000'000;
  Simulator sim(w.world, w.options, w.robot, options, 3);
  while (recorder.scans < scans && sim.step(recorder)) {
  }
  return events;
}

LocalizerProcessConfig localizer_config(const SmallWorld& w) {
  LocalizerProcessConfig config;
  config.localizer.mode = LocalizerMode::kSlamer;
  config.localizer.particles = 150;
  config.localizer.initial_pose = w.options.start;
  config.localizer.initial_sigma = {0.1, 0.1, 0.05};
  return config;
}

std::vector<pose_estimate_t> poses_in(const std::vector<PublishedMessage>& published) {
  std::vector<pose_estimate_t> poses;
  for (const PublishedMessage& m : published) {
    pose_estimate_t pose{};
    if (m.channel == "POSE" && decode_message(m.bytes.data(), m.bytes.size(), &pose) == DecodeStatus::kOk) {
      poses.push_back(pose);
    }
  }
  return poses;
}

std::vector<PublishedMessage> read_log(const std::string& path) {
  std::vector<PublishedMessage> events;
  EventLogReader reader(path);
  while (const std::optional<LogEvent> e = reader.next()) {
    events.push_back({e->channel, e->data, e->timestamp});
  }
  return events;
}

TEST(ProgramWiring, InMemoryAndReplayedRunsGiveTheSamePoses) {
  const SmallWorld w;
  const std::vector<Event> events = simulate(w, 120);
  const LocalizerProcessConfig config = localizer_config(w);
  const RecognizerProcessConfig recognizer_config;

  // Both programs on one in-memory bus: LINE_OBJECTS loop back to the localizer.
  MemoryBus memory("slamer-stack", events.front().utime);
  RecognizerProcess recognizer(memory, recognizer_config);
  LocalizerProcess localizer(memory, config, w.robot, LocalizerNode(w.map, config.localizer, w.robot.lidar.mount),
                             false);
  for (const Event& e : events) {
    memory.inject(e.channel, e.bytes, e.utime);
  }
  ASSERT_EQ(memory.run(), 0);
  const std::vector<pose_estimate_t> in_memory = poses_in(memory.published());

  // The same messages as a log, through each program's replay in turn.
  const auto dir = std::filesystem::temp_directory_path();
  const std::string sensors = (dir / "wiring_sensors.lcm").string();
  const std::string recognized = (dir / "wiring_recognized.lcm").string();
  const std::string localized = (dir / "wiring_localized.lcm").string();
  {
    lcm::LogFile log(sensors, "w");
    for (const Event& e : events) {
      lcm::LogEvent event;
      event.timestamp = e.utime;
      event.channel = e.channel;
      event.datalen = static_cast<int32_t>(e.bytes.size());
      event.data = const_cast<uint8_t*>(e.bytes.data());
      ASSERT_EQ(log.writeEvent(&event), 0);
    }
  }
  {
    LogBus bus("slamer-recognizer", sensors, recognized, recognizer_config.process);
    RecognizerProcess process(bus, recognizer_config);
    ASSERT_EQ(bus.run(), 0);
    EXPECT_EQ(process.scans_recognized(), 120);
  }
  {
    LogBus bus("slamer-localizer", recognized, localized, config.process);
    LocalizerProcess process(bus, config, w.robot, LocalizerNode(w.map, config.localizer, w.robot.lidar.mount), false);
    ASSERT_EQ(bus.run(), 0);
    EXPECT_EQ(process.node().counters().scans_without_objects, 0);
  }
  const std::vector<PublishedMessage> replay_log = read_log(localized);
  const std::vector<pose_estimate_t> replayed = poses_in(replay_log);

  ASSERT_EQ(in_memory.size(), 120u);
  ASSERT_EQ(replayed.size(), in_memory.size());
  for (std::size_t i = 0; i < replayed.size(); ++i) {
    EXPECT_EQ(replayed[i].utime, in_memory[i].utime) << "scan " << i;
    EXPECT_EQ(replayed[i].x, in_memory[i].x) << "scan " << i;
    EXPECT_EQ(replayed[i].y, in_memory[i].y) << "scan " << i;
    EXPECT_EQ(replayed[i].theta, in_memory[i].theta) << "scan " << i;
  }
  // And the pose is right: the last one against the simulator's truth at its scan.
  pose_estimate_t truth{};
  for (const Event& e : events) {
    pose_estimate_t t{};
    if (e.channel == "GROUND_TRUTH" && decode_message(e.bytes.data(), e.bytes.size(), &t) == DecodeStatus::kOk &&
        t.utime <= replayed.back().utime) {
      truth = t;
    }
  }
  EXPECT_THAT(replayed.back(), test::PoseNear(truth, 0.10, 0.05));
  EXPECT_EQ(replayed.back().status, pose_estimate_t::OK);

  // The replay carries both programs' PROCESS_STATUS, with their counters.
  int localizer_status = 0;
  int recognizer_status = 0;
  for (const PublishedMessage& m : replay_log) {
    process_status_t status{};
    if (m.channel == "PROCESS_STATUS" && decode_message(m.bytes.data(), m.bytes.size(), &status) == DecodeStatus::kOk) {
      (status.process == "slamer-localizer" ? localizer_status : recognizer_status) += 1;
      if (status.process == "slamer-localizer") {
        EXPECT_EQ(status.drops, 0);
      }
    }
  }
  EXPECT_GE(localizer_status, 3);  // 120 scans are 3 s: the first, one a second, the last
  EXPECT_GE(recognizer_status, 3);
  for (const std::string& f : {sensors, recognized, localized}) {
    std::remove(f.c_str());
  }
}

template <class Msg>
std::vector<uint8_t> bytes_of(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The fault probing's single messages, each between good ones: none moves the
// estimate, none costs a good scan, each is counted as a drop of its channel.
TEST(ProgramWiring, NoSingleBadMessageMovesTheEstimateOrCostsAGoodScan) {
  const SmallWorld w;
  const std::vector<Event> events = simulate(w, 120);
  const LocalizerProcessConfig config = localizer_config(w);
  const int64_t t0 = events.front().utime;
  MemoryBus bus("slamer-localizer", t0);
  RecognizerProcess recognizer(bus, RecognizerProcessConfig{});
  LocalizerProcess localizer(bus, config, w.robot, LocalizerNode(w.map, config.localizer, w.robot.lidar.mount), false);
  int scans = 0;
  for (const Event& e : events) {
    bus.inject(e.channel, e.bytes, e.utime);
    if (e.channel != "LIDAR" || ++scans % 20 != 10) {
      continue;
    }
    const int64_t at = e.utime + 1;
    odometry_t jump{};  // the right type, a body 5 m away
    jump.utime = at;
    jump.x = 5.0;
    jump.y = -3.0;
    bus.inject("ODOMETRY", bytes_of(jump), at);
    laser_scan_t future{};  // a good scan stamped an hour ahead
    laser_scan_t message = to_message(w.scan_at(w.options.start));
    future = message;
    future.utime = e.utime + 3'600'000'000;
    bus.inject("LIDAR", bytes_of(future), at);
    laser_scan_t zero = message;  // utime 0
    zero.utime = 0;
    bus.inject("LIDAR", bytes_of(zero), at);
    laser_scan_t two_beams = message;  // NaN increment, two beams
    two_beams.utime = e.utime + 2;
    two_beams.angle_increment = std::numeric_limits<float>::quiet_NaN();
    two_beams.ranges.resize(2);
    two_beams.nranges = 2;
    bus.inject("LIDAR", bytes_of(two_beams), at);
    initial_pose_t pose{};  // far off the map, an indefinite covariance
    pose.utime = at;
    pose.x = 1e12;
    pose.y = -1e12;
    pose.cov[0] = 1.0;
    pose.cov[1] = pose.cov[3] = 2.0;
    pose.cov[4] = 1.0;
    bus.inject("INITIAL_POSE", bytes_of(pose), at);
  }
  ASSERT_EQ(bus.run(), 0);
  const std::vector<pose_estimate_t> poses = poses_in(bus.published());
  ASSERT_EQ(poses.size(), 120u) << "a good scan was lost, or a bad one used";
  pose_estimate_t truth{};
  for (const Event& e : events) {
    pose_estimate_t t{};
    if (e.channel == "GROUND_TRUTH" && decode_message(e.bytes.data(), e.bytes.size(), &t) == DecodeStatus::kOk &&
        t.utime <= poses.back().utime) {
      truth = t;
    }
  }
  EXPECT_THAT(poses.back(), test::PoseNear(truth, 0.10, 0.05));
  const process_status_t status = bus.health().status(bus.now());
  std::map<std::string, int64_t> drops;
  for (const channel_stats_t& c : status.channels) {
    if (c.direction == channel_stats_t::SUBSCRIBED) {
      drops[c.channel] = c.drops;
    }
  }
  EXPECT_EQ(drops["INITIAL_POSE"], 6);
  // Each jump there (seq 0 after higher ones, later in time: a driver's restart, so a new
  // reference, not a refusal) and the jump back (refused): neither integrated.
  EXPECT_EQ(drops["ODOMETRY"], 6);
  EXPECT_GE(drops["LIDAR"], 3 * 6);  // future, zero and broken scans (the recognizer counts its own too)
}

}  // namespace
}  // namespace slamer

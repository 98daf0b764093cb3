// slamer-localizer live on LCM, fed by this test over UDP multicast: it takes
// INITIAL_POSE, drops and counts duplicate and out-of-order scans, says in
// PROCESS_STATUS which stream is missing while it keeps publishing POSE, saves
// its pose atomically, resumes from it after a clean stop or a SIGKILL, and
// starts from the config with one warning when the saved file is corrupt.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <thread>

#include "common/process/convert.hpp"
#include "common/process/decode.hpp"
#include "localizer/saved_pose.hpp"
#include "slamer/initial_pose_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/localizer/small_world.hpp"
#include "test/support/child_process.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBinary = SLAMER_BINARY_DIR;

int64_t wall_utime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// The test's end of the bus: sends sensor data, keeps what the localizer says.
class Bus {
 public:
  explicit Bus(const std::string& url) : lcm_(url) {
    // subscribeFunction with a context, as the stack does: LCM's member-function
    // subscription trips UBSan's vptr check inside lcm-cpp-impl.hpp.
    lcm_.subscribeFunction(
        "POSE", +[](const lcm::ReceiveBuffer* rbuf, const std::string&, Bus* self) { self->on_pose(rbuf); }, this);
    lcm_.subscribeFunction(
        "PROCESS_STATUS", +[](const lcm::ReceiveBuffer* rbuf, const std::string&, Bus* self) { self->on_status(rbuf); },
        this);
  }
  bool good() { return lcm_.good(); }

  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
  }
  // Handles incoming messages for `seconds`.
  void listen(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      lcm_.handleTimeout(10);
    }
  }
  // Waits for a PROCESS_STATUS of slamer-localizer (it is subscribed and running); false after `timeout` s.
  bool wait_until_running(double timeout) {
    const std::size_t seen = statuses.size();
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    while (statuses.size() == seen && std::chrono::steady_clock::now() < end) {
      lcm_.handleTimeout(10);
    }
    return statuses.size() > seen;
  }
  // Scans of the small room at `pose` (and unchanging odometry unless `odometry` is false) at
  // 20 Hz for `seconds`, handling what comes back in between.
  void drive(const SmallWorld& w, const Pose2& pose, double seconds, bool odometry = true) {
    LaserScan scan = w.scan_at(pose);
    for (int i = 0; i < static_cast<int>(seconds * 20); ++i) {
      scan.utime = wall_utime();
      scan.seq = seq_++;
      if (odometry) {
        publish("ODOMETRY", make_odometry(scan.utime, scan.seq, {}, 0.0, 0.0));
      }
      publish("LIDAR", to_message(scan));
      listen(0.05);
    }
  }
  void send_scan(const SmallWorld& w, const Pose2& pose, int64_t utime) {
    LaserScan scan = w.scan_at(pose);
    scan.utime = utime;
    scan.seq = seq_++;
    publish("LIDAR", to_message(scan));
  }

  std::vector<pose_estimate_t> poses;
  std::vector<process_status_t> statuses;  // of slamer-localizer

 private:
  void on_pose(const lcm::ReceiveBuffer* rbuf) {
    pose_estimate_t m{};
    if (decode_message(rbuf->data, rbuf->data_size, &m) == DecodeStatus::kOk) {
      poses.push_back(m);
    }
  }
  void on_status(const lcm::ReceiveBuffer* rbuf) {
    process_status_t m{};
    if (decode_message(rbuf->data, rbuf->data_size, &m) == DecodeStatus::kOk && m.process == "slamer-localizer") {
      statuses.push_back(m);
    }
  }

  lcm::LCM lcm_;
  int64_t seq_ = 0;
};

bool any_status_says(const Bus& bus, int8_t state, const std::string& text) {
  for (const process_status_t& s : bus.statuses) {
    if (s.state == state && s.message.find(text) != std::string::npos) {
      return true;
    }
  }
  return false;
}

int64_t lidar_drops(const process_status_t& status) {
  for (const channel_stats_t& c : status.channels) {
    if (c.channel == "LIDAR" && c.direction == channel_stats_t::SUBSCRIBED) {
      return c.drops;
    }
  }
  return -1;
}

double distance(const pose_estimate_t& estimate, const Pose2& pose) {
  return std::hypot(estimate.x - pose.x, estimate.y - pose.y);
}

TEST(SlamerLocalizerLive, InitialPoseFaultsAndResumingFromTheSavedPose) {
  const SmallWorld w;
  const std::string url = test::unique_lcm_url(31);
  const std::string pose_file = kBinary + "/loc_live_pose.yaml";
  std::filesystem::remove(pose_file);
  // The configured start is 1 m from where the robot really is.
  const std::string config = kBinary + "/loc_live.yaml";
  std::ofstream(config) << "map: " << kSource << "/config/maps/small_room/map.yaml\nrobot: " << kSource
                        << "/config/robots/icart_mini.yaml\npose_file: " << pose_file
                        << "\npose_save_period: 0.2\nparticles_out: 0\n"
                        << "localizer: {particles: 200, initial_pose: [1.5, 3.0, 0.0], initial_sigma: [0.05, 0.05, "
                           "0.02]}\n";
  const Pose2 truth{2.5, 3.0, 0.2};
  Bus bus(url);
  ASSERT_TRUE(bus.good());

  {  // 1. INITIAL_POSE, stale scans, no recognizer, then no odometry; a clean stop.
    test::ChildProcess localizer(test::binary_path("slamer-localizer"), {"--lcm-url", url, "--config", config});
    ASSERT_TRUE(bus.wait_until_running(60.0)) << localizer.stderr_text();
    initial_pose_t initial{};
    initial.utime = wall_utime();
    initial.x = truth.x;
    initial.y = truth.y;
    initial.theta = truth.theta;
    initial.cov[0] = initial.cov[4] = 0.05 * 0.05;
    initial.cov[8] = 0.02 * 0.02;
    bus.publish("INITIAL_POSE", initial);
    bus.listen(0.2);
    bus.drive(w, truth, 2.0);
    const int64_t now = wall_utime();
    bus.send_scan(w, truth, now);
    bus.send_scan(w, truth, now);           // the same scan again
    bus.send_scan(w, truth, now - 30'000);  // older than the last
    bus.listen(0.3);
    bus.drive(w, truth, 1.5);
    ASSERT_FALSE(bus.poses.empty()) << localizer.stderr_text();
    EXPECT_LT(distance(bus.poses.back(), truth), 0.05) << "INITIAL_POSE was not used";
    EXPECT_EQ(bus.poses.back().status, pose_estimate_t::OK);
    EXPECT_TRUE(any_status_says(bus, process_status_t::DEGRADED, "no LINE_OBJECTS"));
    ASSERT_FALSE(bus.statuses.empty());
    EXPECT_EQ(lidar_drops(bus.statuses.back()), 2);
    // Odometry stops: POSE goes on, and the status says so.
    const std::size_t poses_before = bus.poses.size();
    bus.drive(w, truth, 2.0, false);
    EXPECT_GT(bus.poses.size(), poses_before + 20);
    EXPECT_TRUE(any_status_says(bus, process_status_t::DEGRADED, "no ODOMETRY for"));
    localizer.signal(SIGTERM);
    ASSERT_EQ(localizer.wait(20.0), std::optional<int>(0)) << localizer.stderr_text();
  }
  const auto saved = load_options<SavedPose>(pose_file);
  EXPECT_LT(std::hypot(saved.pose.x - truth.x, saved.pose.y - truth.y), 0.05);

  {  // 2. A restart resumes there, without INITIAL_POSE; then a SIGKILL.
    bus.poses.clear();
    test::ChildProcess localizer(test::binary_path("slamer-localizer"), {"--lcm-url", url, "--config", config});
    ASSERT_TRUE(bus.wait_until_running(60.0)) << localizer.stderr_text();
    bus.drive(w, truth, 1.5);
    ASSERT_FALSE(bus.poses.empty()) << localizer.stderr_text();
    EXPECT_LT(distance(bus.poses.front(), truth), 0.15) << "did not resume from the saved pose";
    EXPECT_NE(bus.poses.front().status, pose_estimate_t::OK) << "a pose read back is not yet evidence";
    EXPECT_LT(distance(bus.poses.back(), truth), 0.05);
    EXPECT_EQ(bus.poses.back().status, pose_estimate_t::OK) << "the scans confirm the resumed pose";
    EXPECT_NE(localizer.stderr_text().find("since the saved pose: its sigma grown by that time, UNCERTAIN"),
              std::string::npos)
        << localizer.stderr_text();
    EXPECT_NE(localizer.stderr_text().find("resuming from the pose saved in " + pose_file), std::string::npos)
        << localizer.stderr_text();
    localizer.signal(SIGKILL);
    localizer.wait(10.0);
  }
  const auto after_kill = load_options<SavedPose>(pose_file);  // whole, not torn
  EXPECT_LT(std::hypot(after_kill.pose.x - truth.x, after_kill.pose.y - truth.y), 0.05);

  {  // 3. A corrupt file: one warning line, and the configured start.
    std::ofstream(pose_file) << "utime: 12\npose: [2.5, oops\n";
    bus.poses.clear();
    test::ChildProcess localizer(test::binary_path("slamer-localizer"), {"--lcm-url", url, "--config", config});
    ASSERT_TRUE(bus.wait_until_running(60.0)) << localizer.stderr_text();
    bus.drive(w, {1.5, 3.0, 0.0}, 0.5);
    ASSERT_FALSE(bus.poses.empty()) << localizer.stderr_text();
    EXPECT_LT(distance(bus.poses.back(), {1.5, 3.0, 0.0}), 0.1);
    localizer.signal(SIGTERM);
    ASSERT_EQ(localizer.wait(20.0), std::optional<int>(0)) << localizer.stderr_text();
    const std::string err = localizer.stderr_text();
    const std::size_t at = err.find("cannot resume: " + pose_file);
    ASSERT_NE(at, std::string::npos) << err;
    EXPECT_NE(err.find("starting from the configured initial pose", at), std::string::npos) << err;
    EXPECT_EQ(err.find('\n', at), err.find("starting from the configured initial pose", at) + 41) << err;
  }
  std::filesystem::remove(pose_file);
}

}  // namespace
}  // namespace slamer

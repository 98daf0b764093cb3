// The live stack under bad input (issue 10): slamer-sim drives the small room
// live, slamer-recognizer and slamer-localizer run as real processes on
// loopback multicast, and this test, between the simulator's good messages,
// sends every kind of bad message the fault probing found: odometry with a
// random body, random initial poses, a pose far off the map, scans stamped 0
// or an hour ahead, odometry an hour ahead, scans with non-finite geometry,
// too few beams or no usable range, garbage and cut-short bytes. Whenever the
// status says OK the pose is within bound of the simulator's truth, no good
// scan goes without its POSE, and what was refused is counted.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>

#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "test/support/child_process.hpp"
#include "test/support/lcm_test_bus.hpp"

namespace slamer {
namespace {

const std::string kSource = SLAMER_SOURCE_DIR;
const std::string kBinary = SLAMER_BINARY_DIR;
constexpr int64_t kBadSeq = 1'000'000'000;  // the injected scans' seq: the simulator's are far below
constexpr int64_t kHour = 3'600'000'000;

// Sends one bad message of each kind in turn, built from the newest good ones.
class Injector {
 public:
  explicit Injector(test::LcmTestBus* bus) : bus_(bus), rng_(7) {}

  // The next bad message; returns its kind's name.
  std::string inject(const laser_scan_t& good_scan, const odometry_t& good_odometry) {
    const int kind = next_++ % 16;
    laser_scan_t scan = good_scan;
    scan.utime = test::wall_utime();  // "now": newer than the real scan in flight
    scan.seq = kBadSeq + next_;
    odometry_t odometry = good_odometry;
    switch (kind) {
      case 0: {  // the right fingerprint, a random body
        std::vector<uint8_t> bytes = test::LcmTestBus::encode(odometry);
        std::uniform_int_distribution<int> byte(0, 255);
        for (std::size_t i = 8; i < bytes.size(); ++i) {
          bytes[i] = static_cast<uint8_t>(byte(rng_));
        }
        bus_->publish_raw("ODOMETRY", bytes);
        return "random odometry body";
      }
      case 1: {
        initial_pose_t pose{};
        std::uniform_int_distribution<uint64_t> bits;
        auto random_double = [&] {
          const uint64_t b = bits(rng_);
          double d;
          std::memcpy(&d, &b, sizeof d);
          return d;
        };
        pose.utime = static_cast<int64_t>(bits(rng_) >> 1);
        pose.x = random_double();
        pose.y = random_double();
        pose.theta = random_double();
        for (double& c : pose.cov) {
          c = random_double();
        }
        pose.cov[0] = std::abs(pose.cov[0]);  // a negative one asks for global localization: a valid request
        bus_->publish("INITIAL_POSE", pose);
        return "random initial pose";
      }
      case 2: {
        initial_pose_t pose{};
        pose.utime = test::wall_utime();
        pose.x = 1e12;
        pose.y = -1e12;
        pose.cov[0] = pose.cov[4] = pose.cov[8] = 0.01;
        bus_->publish("INITIAL_POSE", pose);
        return "initial pose off the map";
      }
      case 3:
        scan.utime = 0;
        break;
      case 4:
        scan.utime = good_scan.utime + kHour;
        break;
      case 5:
        odometry.utime += kHour;
        odometry.x += 50.0;
        bus_->publish("ODOMETRY", odometry);
        return "odometry an hour ahead";
      case 6:
        scan.angle_increment = std::numeric_limits<float>::quiet_NaN();
        break;
      case 7:
        scan.range_max = std::numeric_limits<float>::quiet_NaN();
        break;
      case 8:
      case 9:
      case 10:
        scan.nranges = kind - 8;  // 0, 1 or 2 beams
        scan.ranges.resize(static_cast<std::size_t>(scan.nranges));
        scan.nintensities = 0;
        scan.intensities.clear();
        break;
      case 11:
        std::fill(scan.ranges.begin(), scan.ranges.end(), std::numeric_limits<float>::quiet_NaN());
        break;
      case 12:
        std::fill(scan.ranges.begin(), scan.ranges.end(), 1e30f);
        break;
      case 13: {
        std::vector<uint8_t> garbage(300);
        std::uniform_int_distribution<int> byte(0, 255);
        for (uint8_t& b : garbage) {
          b = static_cast<uint8_t>(byte(rng_));
        }
        bus_->publish_raw("LIDAR", garbage);
        return "garbage bytes";
      }
      case 14: {
        std::vector<uint8_t> bytes = test::LcmTestBus::encode(scan);
        bytes.resize(bytes.size() / 2);
        bus_->publish_raw("LIDAR", bytes);
        return "cut-short scan";
      }
      default:
        scan.angle_min = std::numeric_limits<float>::infinity();
        break;
    }
    bus_->publish("LIDAR", scan);
    return "bad scan " + std::to_string(kind);
  }
  int sent() const { return next_; }

 private:
  test::LcmTestBus* bus_;
  std::mt19937 rng_;
  int next_ = 0;
};

const pose_estimate_t* truth_at(const std::deque<test::Received<pose_estimate_t>>& truth, int64_t utime) {
  const pose_estimate_t* best = nullptr;
  for (auto it = truth.rbegin(); it != truth.rend(); ++it) {
    if (best == nullptr || std::abs(it->msg.utime - utime) < std::abs(best->utime - utime)) {
      best = &it->msg;
    }
    if (it->msg.utime < utime - 100'000) {
      break;
    }
  }
  return best != nullptr && std::abs(best->utime - utime) <= 20'000 ? best : nullptr;
}

TEST(FaultInjection, BadMessagesBetweenGoodOnesNeitherMoveTheRobotNorCostAScan) {
  const std::string dir = kBinary + "/fault_injection";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/sim.yaml") << "sim: {max_duration: 14.0}\n";
  const std::string config = dir + "/localizer.yaml";
  std::ofstream(config) << "map: " << kSource << "/config/maps/small_room/map.yaml\nrobot: " << kSource
                        << "/config/robots/icart_mini.yaml\nlocalizer: {particles: 200, initial_pose: [1.5, 3.0, "
                           "0.0]}\n";
  const std::string url = test::unique_lcm_url(43);
  test::LcmTestBus bus(url);
  ASSERT_TRUE(bus.good());
  const auto& scans = bus.collect<laser_scan_t>("LIDAR");
  const auto& odometry = bus.collect<odometry_t>("ODOMETRY");
  const auto& truth = bus.collect<pose_estimate_t>("GROUND_TRUTH");
  const auto& poses = bus.collect<pose_estimate_t>("POSE");
  const auto& statuses = bus.collect<process_status_t>("PROCESS_STATUS");
  test::ChildProcess recognizer(test::binary_path("slamer-recognizer"),
                                {"--lcm-url", url, "--config", kSource + "/config/recognizer.yaml"});
  test::ChildProcess localizer(test::binary_path("slamer-localizer"),
                               {"--lcm-url", url, "--config", config, "--mode", "slamer"});
  const auto running = [&](const std::string& name) {
    return std::any_of(statuses.begin(), statuses.end(), [&](const auto& s) { return s.msg.process == name; });
  };
  ASSERT_TRUE(bus.pump_until([&] { return running("slamer-recognizer") && running("slamer-localizer"); }, 60.0))
      << recognizer.stderr_text() << localizer.stderr_text();
  test::ChildProcess sim(test::binary_path("slamer-sim"),
                         {"--lcm-url", url, "--world", kSource + "/config/worlds/small_room.yaml", "--config",
                          dir + "/sim.yaml", "--seed", "3"});
  Injector injector(&bus);
  // A bad message every 100 ms once the simulator is under way (about 4 good scans apart).
  int ticks = 0;
  ASSERT_TRUE(bus.pump_until([&] { return !sim.running(); }, 120.0,
                             [&] {
                               if (++ticks % 2 == 0 && !scans.empty() && !odometry.empty() &&
                                   scans.back().msg.seq < kBadSeq) {
                                 injector.inject(scans.back().msg, odometry.back().msg);
                               }
                             }))
      << sim.stderr_text();
  ASSERT_EQ(sim.wait(5.0), std::optional<int>(0)) << sim.stderr_text();
  bus.pump_for(2.0);  // the last scans through both processes, and a status after them

  std::vector<int64_t> good_scans;
  for (const auto& s : scans) {
    if (s.msg.seq < kBadSeq && s.msg.utime > 0) {
      good_scans.push_back(s.msg.utime);
    }
  }
  ASSERT_GT(good_scans.size(), 400u);
  EXPECT_GT(injector.sent(), 100);
  std::map<int64_t, const pose_estimate_t*> pose_of;
  for (const auto& p : poses) {
    pose_of[p.msg.utime] = &p.msg;
  }
  int missing = 0;
  int ok = 0;
  int ok_far = 0;
  double worst_ok = 0.0;
  for (const int64_t utime : good_scans) {
    const auto found = pose_of.find(utime);
    if (found == pose_of.end()) {
      ++missing;
      continue;
    }
    const pose_estimate_t* t = truth_at(truth, utime);
    if (t == nullptr || found->second->status != pose_estimate_t::OK) {
      continue;
    }
    ++ok;
    const double error = std::hypot(found->second->x - t->x, found->second->y - t->y);
    worst_ok = std::max(worst_ok, error);
    ok_far += error > 0.3;
  }
  std::cout << injector.sent() << " bad messages between " << good_scans.size() << " good scans: " << missing
            << " without a POSE, " << ok << " said OK, the worst of them " << worst_ok << " m off\n";
  EXPECT_EQ(missing, 0) << "good scans without a POSE\n" << localizer.stderr_text();
  EXPECT_EQ(ok_far, 0) << "POSE said OK while more than 0.3 m off (worst " << worst_ok << " m)";
  EXPECT_GT(ok, static_cast<int>(good_scans.size()) * 7 / 10) << "the localizer did not track through the faults";
  // Nothing injected got a POSE, and the refusals were counted.
  for (const auto& p : poses) {
    EXPECT_TRUE(std::binary_search(good_scans.begin(), good_scans.end(), p.msg.utime))
        << "a POSE for a scan that was not the simulator's (utime " << p.msg.utime << ")";
  }
  const process_status_t* last = nullptr;
  for (const auto& s : statuses) {
    last = s.msg.process == "slamer-localizer" ? &s.msg : last;
  }
  ASSERT_NE(last, nullptr);
  int64_t refused = 0;
  for (const channel_stats_t& c : last->channels) {
    if (c.direction == channel_stats_t::SUBSCRIBED) {
      refused += c.drops + c.decode_errors;
    }
  }
  EXPECT_GE(refused, injector.sent() * 9 / 10) << "refusals not counted";
  localizer.signal(SIGINT);
  recognizer.signal(SIGINT);
  EXPECT_EQ(localizer.wait(30.0), std::optional<int>(0)) << localizer.stderr_text();
  EXPECT_EQ(recognizer.wait(30.0), std::optional<int>(0)) << recognizer.stderr_text();
  // Refusals are logged at most once a second, not once a message.
  const std::string err = localizer.stderr_text();
  EXPECT_LT(std::count(err.begin(), err.end(), '\n'), 40) << err;
}

}  // namespace
}  // namespace slamer

// YP-Spur parameter files and the board parameters computed from them, against hand computation.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/wheels/ypspur_params.hpp"
#include "test/wheels/icart_mini_params.hpp"

namespace slamer::tfrog {
namespace {

int32_t find(const std::vector<std::vector<Command>>& groups, Param param, int motor, int* count = nullptr) {
  int32_t value = 0;
  int n = 0;
  for (const auto& group : groups) {
    for (const Command& c : group) {
      if (c.param == static_cast<uint8_t>(param) && c.motor == motor) {
        value = c.value;
        ++n;
      }
    }
  }
  if (count != nullptr) {
    *count = n;
  }
  EXPECT_GT(n, 0) << "param " << static_cast<int>(param) << " motor " << motor << " not sent";
  return value;
}

TEST(YpspurParams, ReadsTheShippedIcartMiniFile) {
  const RobotParams params = RobotParams::from_file(icart_mini_param_file());
  EXPECT_DOUBLE_EQ(params.get("COUNT_REV", 1, 0), 400);
  EXPECT_DOUBLE_EQ(params.get("RADIUS", 0, 0), 0.07455);
  EXPECT_DOUBLE_EQ(params.get("RADIUS", 1, 0), -0.07455);
  const Kinematics k = kinematics_from(params);
  EXPECT_DOUBLE_EQ(k.counts_per_wheel_rev[0], 30000.0);
  EXPECT_DOUBLE_EQ(k.tread, 0.30737);
  EXPECT_DOUBLE_EQ(k.max_vel, 0.9);
  EXPECT_DOUBLE_EQ(k.max_acc_w, 6.28);
}

TEST(YpspurParams, YamlGivesTheSameValues) {
  const auto reader = ConfigReader::from_string(
      "COUNT_REV: 400\nGEAR: 75\n\"RADIUS[0]\": 0.07455\n\"RADIUS[1]\": -0.07455\nTREAD: 0.30737\n", "test.yaml");
  const RobotParams params = RobotParams::from_yaml(reader);
  reader.check_all_keys_used();
  EXPECT_DOUBLE_EQ(params.get("RADIUS", 1, 0), -0.07455);
  EXPECT_DOUBLE_EQ(params.get("GEAR", 1, 0), 75);
  EXPECT_THROW(RobotParams::from_yaml(ConfigReader::from_string("\"RADIUS[2]\": 1\n", "bad.yaml")), ConfigError);
}

TEST(YpspurParams, MalformedFilesGiveOneLineErrors) {
  try {
    RobotParams::parse("COUNT_REV 400\nGEAR seventy\n", "x.param");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("x.param:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RobotParams::parse("GEAR\n", "x.param"), ConfigError);
  EXPECT_THROW(RobotParams::parse("GEAR[3] 1\n", "x.param"), ConfigError);
  EXPECT_THROW(RobotParams::parse("GEAR nan\n", "x.param"), ConfigError);
  EXPECT_THROW(RobotParams::from_file("/nonexistent/robot.param"), ConfigError);
  EXPECT_THROW(kinematics_from(RobotParams::parse("COUNT_REV 400\n", "x.param")), ConfigError);
  // Comments and blank lines are fine; KEY[i] overrides one motor.
  const auto p = RobotParams::parse("# c\n\nGEAR 75 # trailing\nGEAR[1] 50\n", "x.param");
  EXPECT_DOUBLE_EQ(p.get("GEAR", 0, 0), 75);
  EXPECT_DOUBLE_EQ(p.get("GEAR", 1, 0), 50);
}

TEST(YpspurParams, ConnectParametersAreYpSpursFormulas) {
  const RobotParams params = RobotParams::from_file(icart_mini_param_file());
  const auto groups = connect_parameters(params, 1000, 11, 300);
  // Order: watchdog 1200 first, 300 last.
  ASSERT_GE(groups.size(), 6u);
  EXPECT_EQ(groups.front()[0], (Command{65, 0, 1200}));
  EXPECT_EQ(groups.back()[1], (Command{65, 1, 300}));
  EXPECT_EQ(find(groups, Param::kProtocolVersion, 0), 11);
  for (int m = 0; m < 2; ++m) {
    EXPECT_EQ(find(groups, Param::kVsrc, m), 6144);       // 24 V * 256
    EXPECT_EQ(find(groups, Param::kControlCycle, m), 1);  // 0.001 s * 1000
    EXPECT_EQ(find(groups, Param::kMotorPhase, m), 3);
    EXPECT_EQ(find(groups, Param::kPKi, m), 135);      // 65536*1000*0.75/(1e6*0.01515*24) = 135.18
    EXPECT_EQ(find(groups, Param::kPKv, m), 650158);   // 65536*1000*60/(630*24*400*0.001) = 650158.7
    EXPECT_EQ(find(groups, Param::kFrPlus, m), 2000);  // 0.002 * 1e6
    EXPECT_EQ(find(groups, Param::kFrMinus, m), 2000);
    EXPECT_EQ(find(groups, Param::kFrWPlus, m), 157);  // 1e-5 * 1e6 * 2pi/400/0.001 = 157.08
    EXPECT_EQ(find(groups, Param::kToqMax, m), 50000);
    EXPECT_EQ(find(groups, Param::kToqMin, m), -50000);
    EXPECT_EQ(find(groups, Param::kToqLimit, m), 400000);
    EXPECT_EQ(find(groups, Param::kPwmMax, m), 1000);
    EXPECT_EQ(find(groups, Param::kPwmMin, m), -1000);
    EXPECT_EQ(find(groups, Param::kEncRev, m), 400);
    // (0.02 + R^2/2 (M/2 + J/T^2)) / 75 * 256*2pi*1e6/30000 = 36.27
    EXPECT_EQ(find(groups, Param::kInertiaSelf, m), 36);
    EXPECT_EQ(find(groups, Param::kInertiaCross, m), -17);  // -17.76 truncated
    EXPECT_EQ(find(groups, Param::kPiKp, m), 80);
    EXPECT_EQ(find(groups, Param::kPiKi, m), 250);
    EXPECT_EQ(find(groups, Param::kIntMax, m), 1500);  // 0.05 * 400 * 75
    EXPECT_EQ(find(groups, Param::kIntMin, m), -1500);
    int watchdogs = 0;
    find(groups, Param::kWatchDogLimit, m, &watchdogs);
    EXPECT_EQ(watchdogs, 2);
  }
  // A device older than protocol 10 gets no protocol_version.
  for (const auto& group : connect_parameters(params, 1000, 9, 300)) {
    for (const Command& c : group) {
      EXPECT_NE(c.param, static_cast<uint8_t>(Param::kProtocolVersion));
    }
  }
}

}  // namespace
}  // namespace slamer::tfrog

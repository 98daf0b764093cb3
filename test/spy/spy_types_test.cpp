// lcm-spy, started by our launcher, must know every slamer type: this writes
// one message of each type into an LCM log from C++ and has lcm-spy's own type
// lookup (on exactly the class path tools/slamer-spy uses) find and decode it.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "slamer/initial_pose_t.hpp"
#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/pose_estimate_t.hpp"
#include "slamer/process_status_t.hpp"
#include "slamer/semantic_objects_t.hpp"
#include "slamer/velocity_command_t.hpp"
#include "slamer/wheel_encoders_t.hpp"

namespace slamer {
namespace {

std::string run(const std::string& command, int* exit_code) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string output;
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof(buffer), pipe.get()) != nullptr) {
    output += buffer;
  }
  const int status = pclose(pipe.release());
  *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

template <class Msg>
void write(lcm::LogFile& log, const std::string& channel, Msg msg, int64_t utime) {
  msg.utime = utime;
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  lcm::LogEvent event;
  event.timestamp = utime;
  event.channel = channel;
  event.datalen = static_cast<int32_t>(bytes.size());
  event.data = bytes.data();
  ASSERT_EQ(log.writeEvent(&event), 0);
}

TEST(SlamerSpy, LcmSpyFindsAndDecodesEverySlamerType) {
  const std::string bin = std::string(SLAMER_BINARY_DIR "/bin");
  int code = 0;
  std::string classpath = run(bin + "/slamer-spy --print-classpath", &code);
  ASSERT_EQ(code, 0) << classpath;
  while (!classpath.empty() && classpath.back() == '\n') {
    classpath.pop_back();
  }
  ASSERT_NE(classpath.find("slamer_lcmtypes.jar"), std::string::npos) << classpath;

  const std::string log_path = std::string(SLAMER_BINARY_DIR "/spy_types_test.lcm");
  {
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    laser_scan_t scan{};
    scan.frame = "laser";
    line_objects_t objects{};
    semantic_objects_t semantic{};
    particles_t particles{};
    wheel_encoders_t wheels{};
    process_status_t status{};
    write(log, "LIDAR", scan, 1);
    write(log, "WHEEL_ENCODERS", wheels, 2);
    write(log, "ODOMETRY", odometry_t{}, 3);
    write(log, "LINE_OBJECTS", objects, 4);
    write(log, "POSE", pose_estimate_t{}, 5);
    write(log, "SEMANTIC_OBJECTS", semantic, 6);
    write(log, "PARTICLES", particles, 7);
    write(log, "CMD_VEL", velocity_command_t{}, 8);
    write(log, "INITIAL_POSE", initial_pose_t{}, 9);
    write(log, "PROCESS_STATUS", status, 10);
  }

  const std::string checker_dir = std::string(SLAMER_BINARY_DIR "/test/spy_type_check.jar");
  const std::string output = run(
      "java -Djava.awt.headless=true -cp '" + classpath + ":" + checker_dir + "' SpyTypeCheck '" + log_path + "' 2>&1",
      &code);
  EXPECT_EQ(code, 0) << output;
  const char* expected[] = {
      "LIDAR slamer.laser_scan_t utime=1",          "WHEEL_ENCODERS slamer.wheel_encoders_t utime=2",
      "ODOMETRY slamer.odometry_t utime=3",         "LINE_OBJECTS slamer.line_objects_t utime=4",
      "POSE slamer.pose_estimate_t utime=5",        "SEMANTIC_OBJECTS slamer.semantic_objects_t utime=6",
      "PARTICLES slamer.particles_t utime=7",       "CMD_VEL slamer.velocity_command_t utime=8",
      "INITIAL_POSE slamer.initial_pose_t utime=9", "PROCESS_STATUS slamer.process_status_t utime=10",
  };
  for (const char* line : expected) {
    EXPECT_NE(output.find(std::string(line) + "\n"), std::string::npos) << "missing '" << line << "' in:\n" << output;
  }
  std::filesystem::remove(log_path);
}

}  // namespace
}  // namespace slamer

// The session over real descriptors: a socketpair and a pty carry the same
// bytes as TCP; TCP refuses a closed loopback port with a one-line error.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>

#include "drivers/urg/transport.hpp"
#include "drivers/urg/urg_session.hpp"
#include "tools/urg_sim/sim_sensor.hpp"

namespace slamer::urg {
namespace {

int64_t steady_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Runs session <-> sensor across two descriptors for `seconds` of real time.
std::size_t run_over(Transport& driver_side, Transport& sensor_side, const std::string& model, double seconds) {
  std::string error;
  EXPECT_TRUE(driver_side.open(&error)) << error;
  EXPECT_TRUE(sensor_side.open(&error)) << error;
  SimModel m;
  sim_model(model, &m);
  SimSensor sensor(m, {});
  UrgSession session({});
  const int64_t start = steady_us();
  sensor.power_on(start);
  session.connected(start);
  std::size_t scans = 0;
  std::string bytes;
  while (steady_us() - start < static_cast<int64_t>(seconds * 1e6)) {
    const int64_t now = steady_us();
    std::string out = session.take_output();
    if (!out.empty()) {
      EXPECT_TRUE(driver_side.write(out, &error)) << error;
    }
    if (sensor_side.read(&bytes, &error) && !bytes.empty()) {
      sensor.receive(bytes, now);
    }
    const std::string reply = sensor.poll(now);
    if (!reply.empty()) {
      EXPECT_TRUE(sensor_side.write(reply, &error)) << error;
    }
    if (driver_side.read(&bytes, &error) && !bytes.empty()) {
      session.received(bytes, steady_us());
    }
    session.tick(steady_us());
    scans += session.take_scans().size();
    usleep(500);
  }
  return scans;
}

TEST(UrgTransport, SocketPair) {
  int fds[2];
  ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
  FdTransport driver(fds[0], "socketpair"), sensor(fds[1], "socketpair");
  EXPECT_GT(run_over(driver, sensor, "UTM-30LX", 1.0), 10u);
}

TEST(UrgTransport, Pty) {
  int master = -1, slave = -1;
  ASSERT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
  termios tio{};
  tcgetattr(slave, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave, TCSANOW, &tio);
  FdTransport driver(slave, "pty"), sensor(master, "pty");
  EXPECT_GT(run_over(driver, sensor, "URG-04LX", 1.5), 3u);
}

TEST(UrgTransport, TcpRefusedIsOneLine) {
  // A loopback port nobody listens on (bound, then closed).
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  getsockname(s, reinterpret_cast<sockaddr*>(&addr), &len);
  close(s);
  TcpTransport tcp("127.0.0.1", ntohs(addr.sin_port));
  std::string error;
  EXPECT_FALSE(tcp.open(&error));
  EXPECT_NE(error.find("refused"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
  SerialTransport serial("/dev/does-not-exist");
  EXPECT_FALSE(serial.open(&error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
  EXPECT_EQ(serial.baud(), 115200);
  serial.next_baud();
  EXPECT_EQ(serial.baud(), 250000);
}

}  // namespace
}  // namespace slamer::urg

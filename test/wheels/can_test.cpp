// CAN wheel encoders: layouts, the CANopen preset, wrap, velocity, error frames,
// candump logs, and the recvmsg transport over socketpair(AF_UNIX, SOCK_SEQPACKET).
#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>

#include "drivers/wheels/can_decoder.hpp"
#include "drivers/wheels/device_io.hpp"

namespace slamer::can {
namespace {

CanFrame frame(uint32_t id, std::vector<uint8_t> data, int64_t utime, bool extended = false) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.len = static_cast<uint8_t>(data.size());
  std::copy(data.begin(), data.end(), f.data.begin());
  f.utime = utime;
  return f;
}

CanLayout parse_layout(const std::string& yaml) {
  return parse_options<CanLayout>(yaml, "can.yaml");
}

TEST(CanLayout, ExtractsEveryWidthEndianAndSign) {
  WheelField f;
  f.offset = 1;
  f.width = 2;
  f.big_endian = true;
  f.is_signed = true;
  const CanFrame fr = frame(0x10, {0x00, 0xFF, 0xFE, 0x01}, 0);
  EXPECT_EQ(extract(f, fr), -2);
  f.is_signed = false;
  EXPECT_EQ(extract(f, fr), 0xFFFE);
  f.big_endian = false;
  EXPECT_EQ(extract(f, fr), 0xFEFF);
  f.width = 4;
  f.offset = 0;
  f.is_signed = true;
  EXPECT_EQ(extract(f, fr), 0x01FEFF00);
  f.offset = 1;
  EXPECT_FALSE(extract(f, fr));  // needs 5 bytes, has 4
  f.width = 1;
  f.offset = 2;
  EXPECT_EQ(extract(f, fr), -2);
}

TEST(CanLayout, YamlIsStrict) {
  const CanLayout layout = parse_layout(
      "right: {id: 0x1A0, offset: 2, width: 2, endian: big, signed: false}\n"
      "left: {id: 0x18FF0001, extended: true, kind: velocity, scale: 0.5}\n");
  EXPECT_EQ(layout.wheels[0].id, 0x1A0);
  EXPECT_TRUE(layout.wheels[0].big_endian);
  EXPECT_TRUE(layout.wheels[1].extended);
  EXPECT_TRUE(layout.wheels[1].velocity);
  EXPECT_THROW(parse_layout("right: {id: 0x800}\n"), ConfigError);  // standard id too big
  EXPECT_THROW(parse_layout("right: {offset: 6, width: 4}\n"), ConfigError);
  EXPECT_THROW(parse_layout("right: {width: 3}\n"), ConfigError);
  EXPECT_THROW(parse_layout("preset: canopn\n"), ConfigError);
  EXPECT_THROW(parse_layout("right: {idd: 1}\n"), ConfigError);
}

TEST(CanDecoder, CanopenPresetPositionActualValueWithWrap) {
  const CanLayout layout = parse_layout("preset: canopen\nnodes: [5, 6]\n");
  CanDecoder decoder(layout);
  EXPECT_EQ(decoder.ids(), (std::vector<uint32_t>{0x185, 0x186}));
  auto le32 = [](int32_t v) {
    const auto u = static_cast<uint32_t>(v);
    return std::vector<uint8_t>{static_cast<uint8_t>(u), static_cast<uint8_t>(u >> 8), static_cast<uint8_t>(u >> 16),
                                static_cast<uint8_t>(u >> 24)};
  };
  EXPECT_FALSE(decoder.feed(frame(0x185, le32(2147483000), 1000)));
  auto first = decoder.feed(frame(0x186, le32(-5), 1100));
  ASSERT_TRUE(first);
  EXPECT_EQ(first->ticks, (std::array<int64_t, 2>{0, 0}));
  EXPECT_FALSE(decoder.feed(frame(0x185, le32(-2147483000), 6000)));  // wrapped: +1296
  EXPECT_FALSE(decoder.feed(frame(0x999, le32(1), 6050)));            // not ours
  const auto second = decoder.feed(frame(0x186, le32(-105), 6100));
  ASSERT_TRUE(second);
  EXPECT_EQ(second->ticks, (std::array<int64_t, 2>{1296, -100}));
  EXPECT_EQ(second->utime, 6100);
  EXPECT_EQ(decoder.status().frames, 4);
}

TEST(CanDecoder, VelocityFieldsIntegrateAndShortFramesAreCounted) {
  const CanLayout layout =
      parse_layout("right: {id: 0x101, width: 2, kind: velocity}\nleft: {id: 0x102, width: 2, kind: velocity}\n");
  CanDecoder decoder(layout);
  int64_t t = 0;
  std::optional<TickSample> last;
  for (int i = 0; i < 101; ++i, t += 10000) {  // 1000 counts/s and -500 counts/s for 1 s
    decoder.feed(frame(0x101, {0xE8, 0x03}, t));
    if (auto s = decoder.feed(frame(0x102, {0x0C, 0xFE}, t))) {
      last = s;
    }
  }
  ASSERT_TRUE(last);
  EXPECT_EQ(last->ticks[0], 1000);
  EXPECT_EQ(last->ticks[1], -500);
  decoder.feed(frame(0x101, {0xE8}, t));
  EXPECT_EQ(decoder.status().short_frames, 1);
}

TEST(CanDecoder, ErrorFramesSetBusStatus) {
  CanDecoder decoder(CanLayout{});
  CanFrame err = frame(CAN_ERR_BUSOFF, {0, 0, 0, 0, 0, 0, 0, 0}, 0);
  err.error = true;
  decoder.feed(err);
  EXPECT_TRUE(decoder.status().bus_off);
  CanFrame passive = frame(CAN_ERR_CRTL | CAN_ERR_LOSTARB, {0, CAN_ERR_CRTL_RX_PASSIVE, 0, 0, 0, 0, 0, 0}, 0);
  passive.error = true;
  decoder.feed(passive);
  EXPECT_TRUE(decoder.status().error_passive);
  EXPECT_EQ(decoder.status().lost_arbitration, 1);
  CanFrame restarted = frame(CAN_ERR_RESTARTED, {0, 0, 0, 0, 0, 0, 0, 0}, 0);
  restarted.error = true;
  decoder.feed(restarted);
  EXPECT_FALSE(decoder.status().bus_off);
  EXPECT_EQ(decoder.status().error_frames, 3);
}

TEST(Candump, ParsesLogLines) {
  std::string error;
  auto f = parse_candump_line("(1436509052.249713) vcan0 185#E803000000", &error);
  ASSERT_TRUE(f) << error;
  EXPECT_EQ(f->utime, 1436509052249713);
  EXPECT_EQ(f->id, 0x185u);
  EXPECT_EQ(f->len, 5);
  EXPECT_EQ(f->data[1], 0x03);
  f = parse_candump_line("(1.000001) can0 18FF0001#01", &error);
  ASSERT_TRUE(f) << error;
  EXPECT_TRUE(f->extended);
  EXPECT_EQ(f->id, 0x18FF0001u);
  f = parse_candump_line("(1.000001) can0 20000040#0000000000000000", &error);
  ASSERT_TRUE(f) << error;
  EXPECT_TRUE(f->error);
  EXPECT_EQ(f->id, static_cast<uint32_t>(CAN_ERR_BUSOFF));
  f = parse_candump_line("(1.000001) can0 123#R", &error);
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->rtr);
  for (const char* bad :
       {"", "garbage", "(1.5) can0 123#00", "(1.000001) can0 12#00", "(1.000001) can0 123#0",
        "(1.000001) can0 123##0112", "(1.000001) can0 800#00", "(1.000001) can0 123#GG",
        "(1.000001) can0 123#001122334455667788",
        // found by fuzz_can_decode: a second dot, no seconds, seconds that overflow
        "(1..48984) can0 123#00", "(.000001) can0 123#00", "(99999999999999999999999.000001) can0 123#00"}) {
    EXPECT_FALSE(parse_candump_line(bad, &error)) << bad;
    EXPECT_FALSE(error.empty());
  }
}

TEST(CanTransport, RealCanFramesOverASeqpacketSocketpair) {
  int fds[2];
  ASSERT_EQ(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
  enable_timestamps(fds[1]);
  can_frame raw{};
  raw.can_id = 0x185;
  raw.len = 4;
  raw.data[0] = 0x10;
  raw.data[3] = 0x80;
  ASSERT_EQ(write(fds[0], &raw, sizeof(raw)), static_cast<ssize_t>(sizeof(raw)));
  can_frame ext{};
  ext.can_id = 0x18FF0001 | CAN_EFF_FLAG;
  ext.len = 1;
  ASSERT_EQ(write(fds[0], &ext, sizeof(ext)), static_cast<ssize_t>(sizeof(ext)));
  const char garbage[5] = {1, 2, 3, 4, 5};
  ASSERT_EQ(write(fds[0], garbage, sizeof(garbage)), 5);
  CanFrame got;
  std::string error;
  ASSERT_EQ(read_can_frame(fds[1], 42, &got, &error), ReadResult::kFrame) << error;
  EXPECT_EQ(got.id, 0x185u);
  EXPECT_EQ(got.len, 4);
  EXPECT_EQ(got.data[3], 0x80);
  EXPECT_GT(got.utime, 1'600'000'000'000'000);  // SO_TIMESTAMP, not the fallback
  ASSERT_EQ(read_can_frame(fds[1], 42, &got, &error), ReadResult::kFrame);
  EXPECT_TRUE(got.extended);
  EXPECT_EQ(got.id, 0x18FF0001u);
  EXPECT_EQ(read_can_frame(fds[1], 42, &got, &error), ReadResult::kBadSize);
  EXPECT_NE(error.find("5 bytes"), std::string::npos);
  EXPECT_EQ(read_can_frame(fds[1], 42, &got, &error), ReadResult::kWouldBlock);
  close(fds[0]);
  EXPECT_EQ(read_can_frame(fds[1], 42, &got, &error), ReadResult::kClosed);
  close(fds[1]);
  // The helper's bytes are a can_frame too.
  const auto bytes = to_can_frame_bytes(frame(0x7FF, {1, 2}, 0));
  const auto back = parse_can_frame(bytes);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->id, 0x7FFu);
  EXPECT_EQ(back->data[1], 2);
}

TEST(CanTransport, RealVcan0WhenTheKernelHasIt) {
  std::string error;
  const int rx = open_can_socket("vcan0", {0x185}, false, &error);
  if (rx < 0) {
    GTEST_SKIP() << "no vcan0 on this machine (" << error
                 << "); create one with: modprobe vcan && ip link add vcan0 type vcan && ip link set vcan0 up";
  }
  const int tx = open_can_socket("vcan0", {0x185}, false, &error);
  ASSERT_GE(tx, 0) << error;
  can_frame raw{};
  raw.can_id = 0x185;
  raw.len = 4;
  raw.data[0] = 7;
  ASSERT_EQ(write(tx, &raw, sizeof(raw)), static_cast<ssize_t>(sizeof(raw)));
  CanFrame got;
  ReadResult result = ReadResult::kWouldBlock;
  for (int i = 0; i < 100 && result == ReadResult::kWouldBlock; ++i) {
    result = read_can_frame(rx, 0, &got, &error);
    usleep(1000);
  }
  ASSERT_EQ(result, ReadResult::kFrame) << error;
  EXPECT_EQ(got.data[0], 7);
  close(tx);
  close(rx);
}

}  // namespace
}  // namespace slamer::can

// Decoding untrusted bytes: every kind of bad input is classified, never
// crashes, and never makes the decoder allocate what the bytes cannot hold.
#include "common/process/decode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "slamer/laser_scan_t.hpp"
#include "slamer/line_objects_t.hpp"
#include "slamer/odometry_t.hpp"
#include "slamer/particles_t.hpp"
#include "slamer/process_status_t.hpp"

namespace slamer {
namespace {

template <class Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return bytes;
}

laser_scan_t make_scan() {
  laser_scan_t scan;
  scan.utime = 1700000000000000;
  scan.sensor_utime = 123456;
  scan.seq = 42;
  scan.frame = "laser";
  scan.angle_min = -2.356194490192345;
  scan.angle_increment = 0.004363323129985824;
  scan.range_min = 0.1f;
  scan.range_max = 30.0f;
  scan.time_increment = 1.0f / 40.0f / 1440.0f;
  scan.scan_period = 0.025f;
  scan.ranges = {1.0f, std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::quiet_NaN(), 29.5f};
  scan.nranges = static_cast<int32_t>(scan.ranges.size());
  scan.nintensities = 0;
  return scan;
}

// Overwrites the big-endian int32 at `offset`.
void put_int32(std::vector<uint8_t>* bytes, std::size_t offset, int32_t value) {
  const auto u = static_cast<uint32_t>(value);
  (*bytes)[offset] = static_cast<uint8_t>(u >> 24);
  (*bytes)[offset + 1] = static_cast<uint8_t>(u >> 16);
  (*bytes)[offset + 2] = static_cast<uint8_t>(u >> 8);
  (*bytes)[offset + 3] = static_cast<uint8_t>(u);
}

// Offsets in an encoded laser_scan_t with frame "laser" (8 hash + 3x8 int64).
constexpr std::size_t kFrameLengthOffset = 32;
constexpr std::size_t kRangeCountOffset = 36 + 6 + 8 + 8 + 4 * 4;

TEST(DecodeMessage, RoundTripKeepsRep117Values) {
  const laser_scan_t scan = make_scan();
  const std::vector<uint8_t> bytes = encode(scan);
  laser_scan_t decoded;
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), &decoded), DecodeStatus::kOk);
  EXPECT_EQ(decoded.seq, 42);
  EXPECT_EQ(decoded.frame, "laser");
  ASSERT_EQ(decoded.nranges, 5);
  EXPECT_EQ(decoded.ranges[0], 1.0f);
  EXPECT_TRUE(std::isinf(decoded.ranges[1]) && decoded.ranges[1] > 0);
  EXPECT_TRUE(std::isinf(decoded.ranges[2]) && decoded.ranges[2] < 0);
  EXPECT_TRUE(std::isnan(decoded.ranges[3]));
}

TEST(DecodeMessage, DoublesDecodeIntoValueInitializedMessages) {
  // lcm_coretypes.h writes doubles through an int64_t*: without
  // -fno-strict-aliasing, GCC -O2 returned the zeros of the {} below.
  odometry_t sent{};
  sent.utime = 17;
  sent.x = 2.5;
  sent.y = -1.25;
  sent.theta = 0.75;
  sent.v = 0.5;
  sent.omega = -0.125;
  const std::vector<uint8_t> bytes = encode(sent);
  odometry_t got{};
  ASSERT_EQ(decode_message(bytes.data(), bytes.size(), &got), DecodeStatus::kOk);
  EXPECT_EQ(got.x, 2.5);
  EXPECT_EQ(got.y, -1.25);
  EXPECT_EQ(got.theta, 0.75);
  EXPECT_EQ(got.v, 0.5);
  EXPECT_EQ(got.omega, -0.125);
  laser_scan_t scan{};
  const std::vector<uint8_t> scan_bytes = encode(make_scan());
  ASSERT_EQ(decode_message(scan_bytes.data(), scan_bytes.size(), &scan), DecodeStatus::kOk);
  EXPECT_EQ(scan.range_max, 30.0f);
  EXPECT_EQ(scan.angle_increment, 0.004363323129985824);
}

TEST(DecodeMessage, ClassifiesBadInput) {
  const std::vector<uint8_t> bytes = encode(make_scan());
  laser_scan_t decoded;
  EXPECT_EQ(decode_message(bytes.data(), 0, &decoded), DecodeStatus::kTooShort);
  EXPECT_EQ(decode_message(bytes.data(), 7, &decoded), DecodeStatus::kTooShort);

  process_status_t other;
  other.nchannels = 0;
  const std::vector<uint8_t> other_bytes = encode(other);
  EXPECT_EQ(decode_message(other_bytes.data(), other_bytes.size(), &decoded), DecodeStatus::kWrongFingerprint);

  for (std::size_t cut = 8; cut < bytes.size(); ++cut) {
    ASSERT_EQ(decode_message(bytes.data(), cut, &decoded), DecodeStatus::kMalformed) << "cut at " << cut;
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_EQ(decode_message(longer.data(), longer.size(), &decoded), DecodeStatus::kTrailingBytes);
}

TEST(DecodeMessage, ForgedCountsAreRejectedWithoutAllocating) {
  // A count field claiming two billion floats in a 100-byte message: the
  // generated decoder used to resize to 8 GB before noticing.
  const std::vector<uint8_t> bytes = encode(make_scan());
  ASSERT_EQ(bytes[kRangeCountOffset + 3], 5) << "offset of nranges changed";
  for (const int32_t count : {std::numeric_limits<int32_t>::max(), 1 << 30, -1, std::numeric_limits<int32_t>::min()}) {
    std::vector<uint8_t> forged = bytes;
    put_int32(&forged, kRangeCountOffset, count);
    laser_scan_t decoded;
    EXPECT_EQ(decode_message(forged.data(), forged.size(), &decoded), DecodeStatus::kMalformed) << count;
    EXPECT_LT(decoded.ranges.capacity(), 1000u);
  }
}

TEST(DecodeMessage, ForgedStringLengthsAreRejected) {
  const std::vector<uint8_t> bytes = encode(make_scan());
  ASSERT_EQ(bytes[kFrameLengthOffset + 3], 6) << "offset of the frame length changed";  // "laser" + NUL
  for (const int32_t length : {0, -1, -100, std::numeric_limits<int32_t>::min(), 1 << 30}) {
    std::vector<uint8_t> forged = bytes;
    put_int32(&forged, kFrameLengthOffset, length);
    laser_scan_t decoded;
    EXPECT_EQ(decode_message(forged.data(), forged.size(), &decoded), DecodeStatus::kMalformed) << length;
  }
}

TEST(DecodeMessage, StringsMustBeCStrings) {
  // "laser\0" is at kFrameLengthOffset + 4. A string whose last byte is not
  // NUL, or with a NUL inside, would not encode back to the same bytes.
  const std::vector<uint8_t> bytes = encode(make_scan());
  std::vector<uint8_t> unterminated = bytes;
  unterminated[kFrameLengthOffset + 4 + 5] = 'X';
  std::vector<uint8_t> inner_nul = bytes;
  inner_nul[kFrameLengthOffset + 4 + 2] = 0;
  laser_scan_t decoded;
  EXPECT_EQ(decode_message(unterminated.data(), unterminated.size(), &decoded), DecodeStatus::kMalformed);
  EXPECT_EQ(decode_message(inner_nul.data(), inner_nul.size(), &decoded), DecodeStatus::kMalformed);
}

TEST(DecodeMessage, ForgedNestedCountsAreRejected) {
  line_objects_t objects;
  objects.frame = "laser";
  objects.nclasses = 1;
  objects.class_names = {"door"};
  objects.nobjects = 0;
  std::vector<uint8_t> bytes = encode(objects);
  // nobjects is the last int32 of the message.
  put_int32(&bytes, bytes.size() - 4, std::numeric_limits<int32_t>::max());
  line_objects_t decoded;
  EXPECT_EQ(decode_message(bytes.data(), bytes.size(), &decoded), DecodeStatus::kMalformed);

  particles_t particles;
  particles.n = 0;
  std::vector<uint8_t> particle_bytes = encode(particles);
  put_int32(&particle_bytes, particle_bytes.size() - 4, 1 << 29);  // 4 GB per array of doubles
  particles_t decoded_particles;
  EXPECT_EQ(decode_message(particle_bytes.data(), particle_bytes.size(), &decoded_particles), DecodeStatus::kMalformed);
}

TEST(DecodeMessage, RandomBytesWithTheRightFingerprintNeverCrash) {
  const std::vector<uint8_t> valid = encode(make_scan());
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> byte(0, 255);
  int ok = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> bytes = valid;
    const int flips = 1 + trial % 8;
    for (int f = 0; f < flips; ++f) {
      bytes[8 + static_cast<std::size_t>(rng()) % (bytes.size() - 8)] = static_cast<uint8_t>(byte(rng));
    }
    bytes.resize(8 + static_cast<std::size_t>(rng()) % (bytes.size() - 7));
    laser_scan_t decoded;
    const DecodeStatus status = decode_message(bytes.data(), bytes.size(), &decoded);
    if (status == DecodeStatus::kOk) {
      ++ok;
      ASSERT_EQ(decoded.ranges.size(), static_cast<std::size_t>(decoded.nranges));
      ASSERT_EQ(encode(decoded), bytes);  // whatever decodes is canonical
    }
  }
  EXPECT_GT(ok, 0);  // some mutations only touch values, which still decode
}

}  // namespace
}  // namespace slamer

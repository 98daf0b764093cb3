// MD/ME decoding (values straddling data lines), geometry from PP, REP 117 ranges.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "drivers/urg/scip_scan.hpp"

namespace slamer::urg {
namespace {

Reply one_reply(const std::string& bytes) {
  ReplyFramer framer;
  framer.feed(bytes);
  std::vector<std::string> lines;
  EXPECT_TRUE(framer.next(&lines));
  return parse_reply(lines);
}

// Written by hand (checksums computed outside this code): 31 values, the 22nd straddles the line break.
const std::string kMd =
    "MD0000003001000;ab\n99b\n4SAF>\n0?X0@=0@b0010020070C60C[0D@0De0EJ0Eo0FT0G90G^0HC0Hh0IM0J20JW0K<0k\n"
    "Ka0LF0Lk0MP0N50NZ0O?0Od0PI0Pn5\n\n";

TEST(ScanDecode, MdWithStraddlingValue) {
  const Reply reply = one_reply(kMd);
  ScanData scan;
  ASSERT_EQ(decode_scan(reply, &scan), ScanError::kOk);
  EXPECT_EQ(reply.tag, "ab");
  EXPECT_EQ(scan.timestamp_ms, 0x123456u);
  ASSERT_EQ(scan.distances.size(), 31u);
  EXPECT_EQ(scan.distances[0], 1000u);
  EXPECT_EQ(scan.distances[3], 1u);
  EXPECT_EQ(scan.distances[21], 1777u);  // chars 63..65: across the line break
  EXPECT_EQ(scan.distances[30], 2110u);
  EXPECT_TRUE(scan.intensities.empty());
}

TEST(ScanDecode, MeDistanceAndIntensity) {
  const Reply reply = one_reply("ME0000000101000\n99b\n4SAF>\n0GL04\\00G0nPH\n\n");
  ScanData scan;
  ASSERT_EQ(decode_scan(reply, &scan), ScanError::kOk);
  ASSERT_EQ(scan.distances.size(), 2u);
  EXPECT_EQ(scan.distances[0], 1500u);
  EXPECT_EQ(scan.intensities[0], 300u);
  EXPECT_EQ(scan.distances[1], 23u);
  EXPECT_EQ(scan.intensities[1], 4000u);
}

TEST(ScanDecode, ErrorsAreClassified) {
  ScanData scan;
  std::string bad = kMd;
  bad[40] = bad[40] == '0' ? '1' : '0';  // corrupt a data char: checksum fails
  EXPECT_EQ(decode_scan(one_reply(bad), &scan), ScanError::kChecksum);
  // Missing second data line.
  const std::string truncated = kMd.substr(0, kMd.find("Ka0")) + "\n";
  EXPECT_EQ(decode_scan(one_reply(truncated), &scan), ScanError::kTruncated);
  // Echo asking for more values than sent.
  std::string longer = kMd;
  longer.replace(0, 18, "MD0000003101000;ab");
  EXPECT_EQ(decode_scan(one_reply(longer), &scan), ScanError::kTruncated);
  std::string shorter = kMd;
  shorter.replace(0, 18, "MD0000002901000;ab");
  EXPECT_EQ(decode_scan(one_reply(shorter), &scan), ScanError::kLength);
  EXPECT_EQ(decode_scan(one_reply("MD0000003001000\n00P\n\n"), &scan), ScanError::kStatus);
  EXPECT_EQ(decode_scan(one_reply("MDxx\n99b\n\n"), &scan), ScanError::kBadEcho);
}

TEST(ScanDecode, ClusteredCount) {
  ScanParams p;
  p.start = 0;
  p.end = 1080;
  p.cluster = 3;
  EXPECT_EQ(p.expected_values(), 361);
  p.cluster = 1;
  EXPECT_EQ(p.expected_values(), 1081);
  const auto echo = parse_scan_echo("ME0044072502105");
  ASSERT_TRUE(echo.has_value());
  EXPECT_TRUE(echo->intensity);
  EXPECT_EQ(echo->start, 44);
  EXPECT_EQ(echo->end, 725);
  EXPECT_EQ(echo->cluster, 2);
  EXPECT_EQ(echo->skip, 1);
  EXPECT_EQ(echo->scans, 5);
}

KeyValues pp(const std::string& model) {
  KeyValues kv;
  kv.items = {{"MODL", model}, {"DMIN", "23"},   {"DMAX", "60000"}, {"ARES", "1440"},
              {"AMIN", "0"},   {"AMAX", "1080"}, {"AFRT", "540"},   {"SCAN", "2400"}};
  return kv;
}

TEST(Geometry, FromPp) {
  SensorGeometry g;
  std::string error;
  ASSERT_TRUE(parse_geometry(pp("UTM-30LX"), &g, &error)) << error;
  EXPECT_NEAR(g.angle_of_step(g.amin), -540 * 2 * std::numbers::pi / 1440, 1e-12);
  EXPECT_NEAR(g.angle_of_step(g.amin), -3 * std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(g.angle_increment(), 2 * std::numbers::pi / 1440, 1e-15);
  EXPECT_NEAR(g.scan_period(), 0.025, 1e-12);
  EXPECT_NEAR(g.time_increment(), 0.025 / 1440, 1e-15);
  KeyValues missing = pp("UTM-30LX");
  missing.items.erase(missing.items.begin() + 3);
  EXPECT_FALSE(parse_geometry(missing, &g, &error));
  EXPECT_NE(error.find("ARES"), std::string::npos);
}

// SCIP 2.0 C-42-03320B p12: every error code of table 3 (URG-04LX, UBG-04LX-F01,
// UHG-08LX) and table 4 (UTM-30LX) with its REP 117 class.
TEST(Ranges, Rep117ErrorCodes) {
  std::string error;
  SensorGeometry utm;
  ASSERT_TRUE(parse_geometry(pp("UTM-30LX"), &utm, &error));
  EXPECT_FLOAT_EQ(range_from_device(23, utm), 0.023f);  // DMIN is a range
  EXPECT_FLOAT_EQ(range_from_device(1500, utm), 1.5f);
  EXPECT_EQ(range_from_device(1, utm), INFINITY);      // no object in the range
  EXPECT_EQ(range_from_device(2, utm), -INFINITY);     // object is too near
  EXPECT_TRUE(std::isnan(range_from_device(3, utm)));  // measurement error (interference)
  EXPECT_EQ(range_from_device(4, utm), -INFINITY);     // out of range at the near end
  EXPECT_TRUE(std::isnan(range_from_device(5, utm)));  // other errors
  EXPECT_TRUE(std::isnan(range_from_device(0, utm)));  // not in table 4
  EXPECT_TRUE(std::isnan(range_from_device(22, utm)));
  for (const std::string model : {"URG-04LX", "URG-04LX-UG01", "UBG-04LX-F01", "UHG-08LX"}) {
    SensorGeometry g;
    KeyValues kv = pp(model);
    kv.items[1].second = "20";  // DMIN
    ASSERT_TRUE(parse_geometry(kv, &g, &error));
    EXPECT_EQ(range_from_device(0, g), INFINITY) << model;  // possibly at 22 m: beyond the range
    for (uint32_t code = 1; code <= 19; ++code) {
      // 1-2 low intensity, 6-19 errors and others, 3-5 unlisted: none is a distance.
      EXPECT_TRUE(std::isnan(range_from_device(code, g))) << model << " code " << code;
    }
    EXPECT_FLOAT_EQ(range_from_device(20, g), 0.020f) << model;
  }
}

}  // namespace
}  // namespace slamer::urg

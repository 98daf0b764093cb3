// SCIP character codec and command encoding against the specification's examples.
#include <gtest/gtest.h>

#include "drivers/urg/scip_codec.hpp"

namespace slamer::urg {
namespace {

TEST(ScipCodec, ChecksumSpecExamples) {
  EXPECT_EQ(scip_checksum("Hokuyo"), 'o');
  EXPECT_EQ(scip_checksum("00"), 'P');
  EXPECT_EQ(scip_checksum("99"), 'b');
  EXPECT_EQ(scip_checksum("0E"), 'e');
}

TEST(ScipCodec, LineChecksumForms) {
  EXPECT_TRUE(line_checksum_ok("00P"));
  EXPECT_FALSE(line_checksum_ok("00Q"));
  EXPECT_FALSE(line_checksum_ok(""));
  // Real devices: ';' excluded from the sum of KEY:value; lines.
  EXPECT_TRUE(line_checksum_ok("DMIN:23;7"));
  // The inclusive form is accepted too.
  const std::string inclusive = std::string("DMIN:23;") + scip_checksum("DMIN:23;");
  EXPECT_TRUE(line_checksum_ok(inclusive));
  EXPECT_FALSE(line_checksum_ok("DMIN:24;7"));
  // UTM-30LX II quirk: summed only up to "<-".
  EXPECT_TRUE(line_checksum_ok("STAT:Sensor works well. <- Sensor is OK;X"));
  EXPECT_FALSE(line_checksum_ok("STAT:Sensor works well. <- Sensor is OK;Y"));
}

TEST(ScipCodec, DecodeSpecExamples) {
  EXPECT_EQ(scip_decode("CB"), 1234u);
  EXPECT_EQ(scip_decode("1Dh"), 5432u);
  EXPECT_EQ(scip_decode("m2@0"), 16000000u);
  EXPECT_FALSE(scip_decode("").has_value());
  EXPECT_FALSE(scip_decode("0 ").has_value());  // below 0x30
  EXPECT_FALSE(scip_decode("0p").has_value());  // above 0x6F
  EXPECT_FALSE(scip_decode("00000000000").has_value());
}

TEST(ScipCodec, EncodeRoundTrip) {
  EXPECT_EQ(scip_encode(1234, 2), "CB");
  EXPECT_EQ(scip_encode(5432, 3), "1Dh");
  EXPECT_EQ(scip_encode(16000000, 4), "m2@0");
  for (uint64_t v : {0ull, 1ull, 4095ull, 262143ull, 16777215ull}) {
    EXPECT_EQ(scip_decode(scip_encode(v, 4)), v);
  }
  EXPECT_EQ(scip_encode(4096, 2), "00");  // only the low 12 bits fit
}

TEST(ScipCodec, Commands) {
  EXPECT_EQ(scip_command("VV"), "VV\n");
  EXPECT_EQ(scip_command("TM1", "sync7"), "TM1;sync7\n");
  EXPECT_EQ(scip_scan_command(false, 44, 725, 1, 0, 0), "MD0044072501000\n");
  EXPECT_EQ(scip_scan_command(true, 0, 1080, 3, 1, 5, "x"), "ME0000108003105;x\n");
}

}  // namespace
}  // namespace slamer::urg

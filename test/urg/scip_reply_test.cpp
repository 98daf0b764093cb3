// Reply framing, status classification, key:value parsing, SCIP 1.1 replies.
#include <gtest/gtest.h>

#include "drivers/urg/scip_reply.hpp"

namespace slamer::urg {
namespace {

std::vector<Reply> frame_all(const std::string& bytes, std::size_t chunk) {
  ReplyFramer framer;
  std::vector<Reply> replies;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < bytes.size(); i += chunk) {
    framer.feed(std::string_view(bytes).substr(i, chunk));
    while (framer.next(&lines)) {
      replies.push_back(parse_reply(lines));
    }
  }
  return replies;
}

TEST(ReplyFramer, SplitsAtBlankLineWhateverTheSegments) {
  const std::string bytes = "QT\n00P\n\nBM;t1\n02R\n\nVV\n00P\nPROT:SCIP 2.0;N\n\n";
  for (std::size_t chunk : {1u, 2u, 5u, 64u}) {
    const auto replies = frame_all(bytes, chunk);
    ASSERT_EQ(replies.size(), 3u) << chunk;
    EXPECT_EQ(replies[0].command, "QT");
    EXPECT_EQ(replies[0].status, "00");
    EXPECT_TRUE(replies[0].checksum_ok());
    EXPECT_EQ(replies[1].command, "BM");
    EXPECT_EQ(replies[1].tag, "t1");
    EXPECT_EQ(replies[1].status, "02");
    EXPECT_EQ(replies[1].kind(), StatusKind::kBenign);
    EXPECT_EQ(replies[2].lines.size(), 1u);
  }
}

TEST(ReplyFramer, AcceptsCrLf) {
  const auto replies = frame_all("QT\r\n00P\r\n\r\n", 3);
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].status, "00");
  EXPECT_TRUE(replies[0].checksum_ok());
}

TEST(ReplyFramer, DropsOverlongReplyAndResynchronises) {
  ReplyFramer framer(100);
  framer.feed(std::string(300, 'A'));
  std::vector<std::string> lines;
  EXPECT_FALSE(framer.next(&lines));
  framer.feed("\n\nQT\n00P\n\n");
  ASSERT_TRUE(framer.next(&lines));
  EXPECT_EQ(lines[0], "QT");
  EXPECT_EQ(framer.overflows(), 1);
}

TEST(ReplyParse, BadStatusChecksumAndTruncation) {
  const auto replies = frame_all("QT\n00Q\n\nQT\n\n", 4);
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_FALSE(replies[0].checksum_ok());
  EXPECT_TRUE(replies[1].status.empty());
}

TEST(ReplyParse, Scip11) {
  // A URG-04LX at power-up answers QT with a 1-char status.
  auto replies = frame_all("QT\nE\n\nSCIP2.0\n0\n\nV\n0\nVEND:Hokuyo\n\n", 7);
  ASSERT_EQ(replies.size(), 3u);
  EXPECT_TRUE(replies[0].scip1);
  EXPECT_EQ(replies[0].status, "E");
  EXPECT_EQ(replies[1].command, "SCIP2.0");
  EXPECT_TRUE(replies[1].scip1);
  EXPECT_EQ(replies[1].status, "0");
  EXPECT_EQ(replies[2].command, "V");
  EXPECT_EQ(parse_key_values(replies[2]).find("VEND")->c_str(), std::string("Hokuyo"));
}

TEST(StatusCodes, EveryClass) {
  EXPECT_EQ(classify_status("MD", "00"), StatusKind::kOk);
  EXPECT_EQ(classify_status("MD", "99"), StatusKind::kScanData);
  EXPECT_EQ(classify_status("ME", "99"), StatusKind::kScanData);
  EXPECT_EQ(classify_status("VV", "99"), StatusKind::kCommandError);
  EXPECT_EQ(classify_status("BM", "02"), StatusKind::kBenign);
  EXPECT_EQ(classify_status("BM", "01"), StatusKind::kMalfunction);
  EXPECT_EQ(classify_status("TM", "02"), StatusKind::kBenign);
  EXPECT_EQ(classify_status("TM", "03"), StatusKind::kBenign);
  EXPECT_EQ(classify_status("TM", "01"), StatusKind::kCommandError);
  EXPECT_EQ(classify_status("TM", "04"), StatusKind::kCommandError);
  EXPECT_EQ(classify_status("QT", "0E"), StatusKind::kTimeAdjust);
  EXPECT_EQ(classify_status("RB", "01"), StatusKind::kBenign);
  EXPECT_EQ(classify_status("SS", "0F"), StatusKind::kBenign);
  EXPECT_EQ(classify_status("MD", "98"), StatusKind::kBenign);
  for (const char* code :
       {"01", "02", "03", "04", "05", "06", "07", "0A", "0B", "0C", "0D", "0F", "0G", "0H", "0I", "10"}) {
    EXPECT_EQ(classify_status("MD", code), StatusKind::kCommandError) << code;
  }
  for (const char* code : {"21", "35", "49", "50", "75", "97"}) {
    EXPECT_EQ(classify_status("MD", code), StatusKind::kMalfunction) << code;
  }
  EXPECT_EQ(classify_status("MD", "0L"), StatusKind::kMalfunction);
  EXPECT_EQ(classify_status("II", "0L"), StatusKind::kMalfunction);
}

TEST(KeyValues, PpReplyOfUtm30lx) {
  const std::string bytes =
      "PP\n00P\nMODL:UTM-30LX;@\nDMIN:23;7\nDMAX:60000;J\nARES:1440;^\nAMIN:0;?\nAMAX:1080;Z\nAFRT:540;0\n"
      "SCAN:2400;U\nDMIN:24;7\n\n";
  const auto replies = frame_all(bytes, 9);
  ASSERT_EQ(replies.size(), 1u);
  const KeyValues kv = parse_key_values(replies[0]);
  EXPECT_EQ(kv.items.size(), 8u);
  EXPECT_EQ(kv.bad_lines, 1);  // the last line's checksum is wrong
  EXPECT_EQ(*kv.find("DMAX"), "60000");
  EXPECT_EQ(*kv.find("MODL"), "UTM-30LX");
  EXPECT_EQ(kv.find("NOPE"), nullptr);
}

TEST(KeyValues, Utm30lxArrowQuirk) {
  const auto replies = frame_all("II\n00P\nSTAT:Sensor works well. <- Sensor is OK;X\n\n", 100);
  const KeyValues kv = parse_key_values(replies.at(0));
  EXPECT_EQ(kv.bad_lines, 0);
  EXPECT_EQ(*kv.find("STAT"), "Sensor works well.");
}

}  // namespace
}  // namespace slamer::urg

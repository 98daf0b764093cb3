// T-frog codec against tfrog.md section 8's worked examples and hand-computed bytes.
#include <gtest/gtest.h>

#include "drivers/wheels/tfrog_codec.hpp"
#include "drivers/wheels/tfrog_text.hpp"

namespace slamer::tfrog {
namespace {

using Bytes = std::vector<uint8_t>;

TEST(TfrogCodec, CommandsMatchTheSpecExamples) {
  EXPECT_EQ(encode_command(Param::kServo, 0, 3), (Bytes{0x09, 0x50, 0x40, 0x40, 0x40, 0x40, 0x40, 0x40, 0x43, 0x0A}));
  EXPECT_EQ(encode_command(Param::kServo, 1, 0), (Bytes{0x09, 0x50, 0x40, 0x44, 0x40, 0x40, 0x40, 0x40, 0x40, 0x0A}));
  EXPECT_EQ(encode_command(Param::kWatchDogLimit, 0, 1200),
            (Bytes{0x09, 0x50, 0x50, 0x40, 0x40, 0x40, 0x40, 0x52, 0x70, 0x0A}));
  EXPECT_EQ(encode_command(Param::kWRef, 0, -100), (Bytes{0x09, 0x40, 0x40, 0x43, 0x7F, 0x7F, 0x7F, 0x7E, 0x5C, 0x0A}));
  EXPECT_EQ(encode_command(Param::kPing, kBroadcastMotor, 0x123456),
            (Bytes{0x09, 0x59, 0x57, 0x78, 0x40, 0x44, 0x63, 0x51, 0x56, 0x0A}));
  const auto record = command_record({0, 0, -100});
  EXPECT_EQ(Bytes(record.begin(), record.end()), (Bytes{0x00, 0x00, 0xFF, 0xFF, 0xFF, 0x9C}));
}

TEST(TfrogCodec, OdometryFrameMatchesTheSpecExample) {
  const Bytes wire = {0x09, 0x40, 0x7E, 0x63, 0x7F, 0x7F, 0x60, 0x40, 0x72, 0x7F, 0x7C, 0x78, 0x0A};
  StreamSplitter splitter;
  std::vector<StreamItem> items;
  splitter.feed(wire, &items);
  ASSERT_EQ(items.size(), 1u);
  ASSERT_EQ(items[0].kind, StreamItem::Kind::kIsochronous);
  EXPECT_EQ(items[0].raw, (Bytes{0x03, 0xE8, 0xFF, 0xFE, 0x00, 0x32, 0xFF, 0xCE}));
  const auto frame = decode_odometry(items[0].raw, 2, 0);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->count, (std::vector<int16_t>{1000, -2}));
  EXPECT_EQ(frame->pwm, (std::vector<int16_t>{50, -50}));
  EXPECT_EQ(encode_frame(kStartIsochronous, encode_odometry(*frame)), wire);
}

TEST(TfrogCodec, InterruptFrameMatchesTheSpecExample) {
  const Bytes wire = {0x07, 0x40, 0x60, 0x40, 0x40, 0x40, 0x40, 0x40, 0x48, 0x0A};
  StreamSplitter splitter;
  std::vector<StreamItem> items;
  splitter.feed(wire, &items);
  ASSERT_EQ(items.size(), 1u);
  ASSERT_EQ(items[0].kind, StreamItem::Kind::kInterrupt);
  const auto event = decode_interrupt(items[0].raw);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->event, static_cast<uint8_t>(Event::kErrorState));
  EXPECT_EQ(event->motor, 0);
  EXPECT_EQ(event->value, kErrorWatchdog);
  EXPECT_EQ(error_bits_text(kErrorWatchdog | kErrorLowVoltage), "LOW_VOLTAGE|WATCHDOG");
  EXPECT_EQ(encode_frame(kStartInterrupt, command_record({2, 0, 8})), wire);
}

TEST(TfrogCodec, PayloadLengthsAndRoundTrip) {
  EXPECT_EQ(encode_payload(Bytes(6, 0)).size(), 8u);
  EXPECT_EQ(encode_payload(Bytes(8, 0)).size(), 11u);
  EXPECT_EQ(encode_payload(Bytes(2, 0)).size(), 3u);
  // 0xFF 0xFF -> 111111 111111 1111(00) -> 0x7F 0x7F 0x7C
  EXPECT_EQ(encode_payload(Bytes{0xFF, 0xFF}), "\x7F\x7F\x7C");
  for (int n = 0; n < 20; ++n) {
    Bytes raw;
    for (int i = 0; i < n; ++i) {
      raw.push_back(static_cast<uint8_t>(37 * i + n));
    }
    const std::string chars = encode_payload(raw);
    for (const char c : chars) {
      ASSERT_GE(static_cast<uint8_t>(c), 0x40);
      ASSERT_LE(static_cast<uint8_t>(c), 0x7F);
    }
    EXPECT_EQ(decode_payload(chars), raw) << n;
  }
  EXPECT_FALSE(decode_payload("\x40\x3F"));
  const auto command = parse_command_record(command_record({65, 1, -2147483646}));
  ASSERT_TRUE(command);
  EXPECT_EQ(*command, (Command{65, 1, -2147483646}));
  EXPECT_FALSE(parse_command_record(Bytes(5, 0)));
}

TEST(TfrogCodec, WrongLengthOdometryIsRejected) {
  EXPECT_FALSE(decode_odometry(Bytes(6, 0), 2, 0));
  EXPECT_FALSE(decode_odometry(Bytes(9, 0), 2, 0));
  const auto with_ad = decode_odometry(Bytes{0, 1, 0, 2, 0, 3, 0, 4, 0x1F, 0xFF}, 2, 1);
  ASSERT_TRUE(with_ad);
  EXPECT_EQ(with_ad->words, (std::vector<uint16_t>{0x1FFF}));
  EXPECT_FALSE(decode_interrupt(Bytes(7, 0)));
}

TEST(TfrogCodec, SplitterSeparatesTextFramesAndDamage) {
  StreamSplitter splitter;
  std::vector<StreamItem> items;
  Bytes stream = {'V', 'V', '\n', '0', '0', 'P', '\n', '\n'};
  const auto frame = encode_command(Param::kServo, 0, 3);
  stream.insert(stream.end(), frame.begin(), frame.end());
  stream.insert(stream.end(), {0x09, 0x50, 0x20, 0x40, 0x0A});        // char below 0x40
  stream.insert(stream.end(), {0x09, 0x50, 0x40, 0x07, 0x40, 0x0A});  // cut by another start
  // Split the stream at every byte to check the state carries over feeds.
  for (const uint8_t byte : stream) {
    splitter.feed(std::span<const uint8_t>(&byte, 1), &items);
  }
  ASSERT_EQ(items.size(), 7u);
  EXPECT_EQ(items[0].text, "VV");
  EXPECT_EQ(items[1].text, "00P");
  EXPECT_EQ(items[2].text, "");
  EXPECT_EQ(items[3].kind, StreamItem::Kind::kIsochronous);
  EXPECT_EQ(items[4].kind, StreamItem::Kind::kBadFrame);
  EXPECT_EQ(items[5].kind, StreamItem::Kind::kBadFrame);
  EXPECT_EQ(items[6].kind, StreamItem::Kind::kInterrupt);  // "\x07\x40" decodes to no bytes
  EXPECT_TRUE(items[6].raw.empty());
}

TEST(TfrogText, VersionReplyAndCompatibility) {
  ReplyCollector collector("VV");
  const std::vector<std::string> lines = {"",
                                          "VV",
                                          "00P",
                                          "VEND:T-frog Prject; ",
                                          "PROD:T-frog Motor Driver rev.5; ",
                                          "FIRM:fcf3734; ",
                                          "PROT:YPP:11:02; ",
                                          "SERI:01300000; ",
                                          "ID:0; ",
                                          ""};
  bool done = false;
  for (const auto& line : lines) {
    done = collector.add_line(line);
  }
  ASSERT_TRUE(done);
  EXPECT_TRUE(collector.reply().ok());
  std::string error;
  const auto identity = parse_vv(collector.reply().body, &error);
  ASSERT_TRUE(identity) << error;
  EXPECT_EQ(identity->vendor, "T-frog Prject");
  EXPECT_EQ(identity->serial, "01300000");
  EXPECT_EQ(identity->protocol_current, 11);
  EXPECT_EQ(identity->protocol_age, 2);
  // YPP:11:05 accepts devices 6..11 (and newer ones whose age reaches back to 11).
  EXPECT_TRUE(protocol_compatible(6, 0));
  EXPECT_TRUE(protocol_compatible(11, 2));
  EXPECT_FALSE(protocol_compatible(5, 0));
  EXPECT_FALSE(protocol_compatible(13, 1));
  EXPECT_TRUE(protocol_compatible(13, 2));
  EXPECT_FALSE(parse_vv({"VEND:x; ", "PROT:XYZ; "}, &error));
  EXPECT_NE(error.find("XYZ"), std::string::npos);
  EXPECT_FALSE(parse_vv({"VEND:x; "}, &error));
}

TEST(TfrogText, ParameterReply) {
  std::string error;
  const auto board = parse_pp({"NAME:embedded; ", "PWMRES:1000; ", "MOTORNUM:2; ", "PARAM:text; "}, &error);
  ASSERT_TRUE(board) << error;
  EXPECT_EQ(board->name, "embedded");
  EXPECT_EQ(board->pwm_resolution, 1000);
  EXPECT_EQ(board->motor_num, 2);
  EXPECT_FALSE(parse_pp({"NAME:x; ", "MOTORNUM:2; "}, &error));
  EXPECT_NE(error.find("PWMRES"), std::string::npos);
  EXPECT_FALSE(parse_pp({"PWMRES:abc; ", "MOTORNUM:2; "}, &error));
  EXPECT_EQ(embedded_param_text({"COUNT_REV 400", "GEAR 75"}), "COUNT_REV 400\nGEAR 75\n");
  ReplyCollector failing("PP");
  failing.add_line("PP");
  EXPECT_TRUE(failing.add_line("0Ee") == false);
  EXPECT_TRUE(failing.add_line(""));
  EXPECT_FALSE(failing.reply().ok());
}

}  // namespace
}  // namespace slamer::tfrog

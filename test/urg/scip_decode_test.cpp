// slamer-scip-decode: specification examples as JSON lines; a file, a missing file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "test/support/child_process.hpp"
#include "tools/scip_decode/scip_json.hpp"

namespace slamer::urg {
namespace {

Reply one(const std::string& bytes) {
  ReplyFramer framer;
  framer.feed(bytes);
  std::vector<std::string> lines;
  EXPECT_TRUE(framer.next(&lines));
  return parse_reply(lines);
}

TEST(ScipJson, ScanAndKeyValues) {
  EXPECT_EQ(reply_to_json(one("ME0000000101000\n99b\n4SAF>\n0GL04\\00G0nPH\n\n")),
            "{\"echo\":\"ME0000000101000\",\"command\":\"ME\",\"status\":\"99\",\"status_kind\":\"scan_data\","
            "\"checksum_ok\":true,\"timestamp\":1193046,\"ranges\":[1500,23],\"intensities\":[300,4000]}");
  EXPECT_EQ(reply_to_json(one("PP\n00P\nDMIN:23;7\nDMAX:6000;J\n\n")),
            "{\"echo\":\"PP\",\"command\":\"PP\",\"status\":\"00\",\"status_kind\":\"ok\",\"checksum_ok\":false,"
            "\"values\":{\"DMIN\":\"23\"},\"bad_lines\":1}");
  EXPECT_NE(reply_to_json(one("ME0000000101000\n99b\n4SAF>\n0GL04\\00G0nPI\n\n")).find("\"scan_error\":\"checksum\""),
            std::string::npos);
}

TEST(ScipDecodeProgram, FileAndMissingFile) {
  const std::string path = std::filesystem::temp_directory_path() / ("scip_decode_" + std::to_string(getpid()));
  {
    std::ofstream out(path, std::ios::binary);
    out << "QT\n00P\n\nTM1\n00P\nm2@0"
        << "\n\nVV\n00P\nPROT:SCIP 2.0;N\n\nQT\n";
  }
  test::ChildProcess file(test::binary_path("slamer-scip-decode"), {path});
  ASSERT_EQ(file.wait(10), 0);
  const std::string text = file.stdout_text();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;
  EXPECT_NE(text.find("\"PROT\":\"SCIP 2.0\""), std::string::npos) << text;
  EXPECT_NE(file.stderr_text().find("without their blank line"), std::string::npos);
  test::ChildProcess missing(test::binary_path("slamer-scip-decode"), {path + ".absent"});
  EXPECT_EQ(missing.wait(10), 1);
  EXPECT_NE(missing.stderr_text().find("cannot open"), std::string::npos);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace slamer::urg

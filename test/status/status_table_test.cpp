#include "tools/status/status_table.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace slamer {
namespace {

process_status_t make_status(const std::string& name, int32_t pid, int8_t state, const std::string& message) {
  process_status_t s;
  s.utime = 0;
  s.process = name;
  s.pid = pid;
  s.state = state;
  s.message = message;
  s.uptime = 1.0;
  s.messages_in = 10;
  s.messages_out = 5;
  s.decode_errors = 2;
  s.drops = 1;
  s.processing_time_p50 = 0.0015;
  s.processing_time_p99 = 0.004;
  s.nchannels = 0;
  return s;
}

TEST(StatusTable, ExpectationsSeeAbsentStaleAndErrors) {
  StatusTable table(3.0);
  table.update(make_status("slamer-recognizer", 10, process_status_t::OK, ""), 1'000'000);
  table.update(make_status("slamer-localizer", 11, process_status_t::ERROR, "map missing"), 1'000'000);
  table.update(make_status("slamer-urg", 12, process_status_t::DEGRADED, "reconnecting"), 1'000'000);

  EXPECT_TRUE(table.check_expected({"slamer-recognizer", "slamer-urg"}, 2'000'000).empty());
  const std::vector<std::string> problems =
      table.check_expected({"slamer-recognizer", "slamer-localizer", "slamer-wheels"}, 2'000'000);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0], "slamer-localizer: error: map missing");
  EXPECT_EQ(problems[1], "slamer-wheels: no status received");
  EXPECT_EQ(table.check_expected({"slamer-recognizer"}, 5'000'000),
            std::vector<std::string>{"slamer-recognizer: no status for 4 s"});
}

TEST(StatusTable, RestartedProcessIsJudgedByItsNewestStatus) {
  StatusTable table(3.0);
  table.update(make_status("slamer-urg", 1, process_status_t::ERROR, "crashed"), 1'000'000);
  table.update(make_status("slamer-urg", 2, process_status_t::OK, ""), 5'000'000);
  EXPECT_TRUE(table.check_expected({"slamer-urg"}, 6'000'000).empty());
}

TEST(StatusTable, RendersTextAndJson) {
  StatusTable table(3.0);
  table.update(make_status("slamer-urg", 12, process_status_t::DEGRADED, "say \"hi\""), 1'000'000);
  const std::string text = table.render_text(1'500'000);
  EXPECT_NE(text.find("slamer-urg"), std::string::npos);
  EXPECT_NE(text.find("degraded"), std::string::npos);
  EXPECT_NE(text.find("1.500"), std::string::npos);  // p50 in ms
  const nlohmann::json json = nlohmann::json::parse(table.render_json(9'000'000));
  const nlohmann::json& urg = json.at("processes").at(0);
  EXPECT_EQ(urg.at("state"), "gone");
  EXPECT_EQ(urg.at("message"), "say \"hi\"");
  EXPECT_EQ(urg.at("decode_errors"), 2);
  EXPECT_EQ(urg.at("pid"), 12);
}

}  // namespace
}  // namespace slamer

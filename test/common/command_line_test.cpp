#include "common/process/command_line.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace slamer {
namespace {

CommandLine make() {
  CommandLine cli("slamer-x", "Does x.");
  cli.add_option("config", "FILE", "config file");
  cli.add_option("seed", "N", "random seed", "1");
  cli.add_flag("json", "print JSON");
  cli.set_positional("LOG", "input logs", 0, 2);
  return cli;
}

bool parse(CommandLine& cli, std::vector<const char*> args, std::string* help = nullptr) {
  args.insert(args.begin(), "slamer-x");
  std::ostringstream out;
  const bool go_on = cli.parse(static_cast<int>(args.size()), args.data(), out);
  if (help != nullptr) {
    *help = out.str();
  }
  return go_on;
}

TEST(CommandLine, OptionsFlagsAndPositionals) {
  CommandLine cli = make();
  ASSERT_TRUE(parse(cli, {"--config", "a.yaml", "--seed=7", "--json", "x.lcm"}));
  EXPECT_EQ(cli.get("config"), "a.yaml");
  EXPECT_EQ(cli.get_int("seed"), 7);
  EXPECT_TRUE(cli.has("json"));
  EXPECT_EQ(cli.positional(), std::vector<std::string>{"x.lcm"});
}

TEST(CommandLine, MultiValueOptionTakesExactlyItsCountIncludingNegativeNumbers) {
  CommandLine cli = make();
  cli.add_multi_option("initial-pose", 3, "X Y THETA", "start pose");
  ASSERT_TRUE(parse(cli, {"--initial-pose", "1.5", "-2", "-0.25", "x.lcm"}));
  const std::vector<double> pose = cli.get_doubles("initial-pose");
  ASSERT_EQ(pose.size(), 3u);
  EXPECT_DOUBLE_EQ(pose[0], 1.5);
  EXPECT_DOUBLE_EQ(pose[1], -2.0);
  EXPECT_DOUBLE_EQ(pose[2], -0.25);
  EXPECT_EQ(cli.positional(), std::vector<std::string>{"x.lcm"});
  CommandLine short_of_values = make();
  short_of_values.add_multi_option("initial-pose", 3, "X Y THETA", "start pose");
  EXPECT_THROW(parse(short_of_values, {"--initial-pose", "1", "2"}), CommandLineError);
  CommandLine not_numbers = make();
  not_numbers.add_multi_option("initial-pose", 3, "X Y THETA", "start pose");
  ASSERT_TRUE(parse(not_numbers, {"--initial-pose", "1", "x", "2"}));
  EXPECT_THROW(not_numbers.get_doubles("initial-pose"), CommandLineError);
}

TEST(CommandLine, DefaultsWhenAbsent) {
  CommandLine cli = make();
  ASSERT_TRUE(parse(cli, {}));
  EXPECT_FALSE(cli.has("config"));
  EXPECT_EQ(cli.get("config"), "");
  EXPECT_EQ(cli.get_int("seed"), 1);
  EXPECT_FALSE(cli.has("json"));
}

TEST(CommandLine, HelpListsEveryOption) {
  CommandLine cli = make();
  std::string help;
  EXPECT_FALSE(parse(cli, {"--help"}, &help));
  EXPECT_NE(help.find("usage: slamer-x [options] [LOG...]"), std::string::npos) << help;
  EXPECT_NE(help.find("--seed N"), std::string::npos);
  EXPECT_NE(help.find("(default: 1)"), std::string::npos);
  EXPECT_NE(help.find("--json"), std::string::npos);
}

TEST(CommandLine, ErrorsNameTheOption) {
  const auto error = [](std::vector<const char*> args) -> std::string {
    CommandLine cli = make();
    try {
      parse(cli, args);
      cli.get_int("seed");
    } catch (const CommandLineError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error({"--sede", "3"}), "unknown option '--sede' (see --help)");
  EXPECT_EQ(error({"-s"}), "unknown option '-s' (options are written --name; see --help)");
  EXPECT_EQ(error({"--config"}), "option '--config' needs a value FILE");
  EXPECT_EQ(error({"--json=1"}), "option '--json' takes no value");
  EXPECT_EQ(error({"--seed", "x"}), "option '--seed': expected an integer, got 'x'");
  EXPECT_EQ(error({"--seed", "3x"}), "option '--seed': expected an integer, got '3x'");
  EXPECT_EQ(error({"a", "b", "c"}), "expected 0 to 2 LOG argument(s), got 3");
}

TEST(CommandLine, DoubleDashEndsOptions) {
  CommandLine cli = make();
  ASSERT_TRUE(parse(cli, {"--", "--json"}));
  EXPECT_FALSE(cli.has("json"));
  EXPECT_EQ(cli.positional(), std::vector<std::string>{"--json"});
}

}  // namespace
}  // namespace slamer

#include "common/config/config_reader.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace slamer {
namespace {

struct TestLidarOptions {
  double range_max = 30.0;
  int beams = 1081;
  bool flip = false;
  std::string frame = "laser";
  std::vector<double> mount{0.0, 0.0, 0.0};
};

struct ClassEntry {
  std::string name;
  std::vector<double> color;
};

struct TestOptions {
  std::string mode = "slamer";
  double alpha = 0.5;
  int64_t seed = 1;
  TestLidarOptions lidar;
  std::vector<ClassEntry> classes;
};

void read_options(const ConfigReader& reader, TestOptions* options) {
  reader.read_choice("mode", &options->mode, {"lfm", "slfm", "slamer"});
  reader.read("alpha", &options->alpha, probability());
  reader.read("seed", &options->seed, non_negative());
  const ConfigReader lidar = reader.section("lidar");
  lidar.read("range_max", &options->lidar.range_max, positive());
  lidar.read("beams", &options->lidar.beams, at_least(1));
  lidar.read("flip", &options->lidar.flip);
  lidar.read("frame", &options->lidar.frame);
  lidar.read("mount", &options->lidar.mount, {}, 3);
  for (const ConfigReader& entry : reader.list("classes")) {
    ClassEntry c;
    entry.require("name");
    entry.read("name", &c.name);
    entry.read("color", &c.color, in_range(0, 255), 3);
    options->classes.push_back(c);
  }
}

// The message of the ConfigError that parsing `yaml` throws ("" if none).
std::string error_of(const std::string& yaml) {
  try {
    parse_options<TestOptions>(yaml, "test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigReader, EmptyDocumentKeepsDefaults) {
  const TestOptions options = parse_options<TestOptions>("", "empty.yaml");
  EXPECT_EQ(options.mode, "slamer");
  EXPECT_DOUBLE_EQ(options.lidar.range_max, 30.0);
  EXPECT_EQ(options.lidar.beams, 1081);
}

TEST(ConfigReader, ReadsEveryType) {
  const TestOptions options = parse_options<TestOptions>(R"(
mode: lfm
alpha: 0.25
seed: 9000000000
lidar:
  range_max: 40
  beams: 721
  flip: true
  frame: urg
  mount: [0.1, -0.2, 3.14]
classes:
  - {name: door, color: [255, 0, 255]}
  - name: fence
    color: [255, 128, 0]
)",
                                                         "full.yaml");
  EXPECT_EQ(options.mode, "lfm");
  EXPECT_DOUBLE_EQ(options.alpha, 0.25);
  EXPECT_EQ(options.seed, 9000000000LL);
  EXPECT_DOUBLE_EQ(options.lidar.range_max, 40.0);
  EXPECT_EQ(options.lidar.beams, 721);
  EXPECT_TRUE(options.lidar.flip);
  EXPECT_EQ(options.lidar.frame, "urg");
  EXPECT_EQ(options.lidar.mount, (std::vector<double>{0.1, -0.2, 3.14}));
  ASSERT_EQ(options.classes.size(), 2u);
  EXPECT_EQ(options.classes[1].name, "fence");
  EXPECT_EQ(options.classes[1].color, (std::vector<double>{255, 128, 0}));
}

TEST(ConfigReader, UnknownKeysAreRejectedWithTheirPathAndLine) {
  EXPECT_EQ(error_of("mode: lfm\nalpah: 0.3\n"), "test.yaml:2: unknown key 'alpah'");
  EXPECT_EQ(error_of("lidar:\n  range_max: 3\n  rnage_min: 1\n"), "test.yaml:3: unknown key 'lidar.rnage_min'");
  EXPECT_EQ(error_of("classes:\n  - {name: door, colour: [1, 2, 3]}\n"),
            "test.yaml:2: unknown key 'classes[0].colour'");
  EXPECT_EQ(error_of("radar: {}\n"), "test.yaml:1: unknown key 'radar'");
}

TEST(ConfigReader, AKeyWrittenTwiceIsRejectedWithBothLines) {
  EXPECT_EQ(error_of("mode: lfm\nalpha: 0.3\nmode: slamer\n"),
            "test.yaml:3: key 'mode' appears twice (first on line 1)");
  EXPECT_EQ(error_of("lidar:\n  beams: 2\n  frame: a\n  beams: 3\n"),
            "test.yaml:4: key 'lidar.beams' appears twice (first on line 2)");
  EXPECT_EQ(error_of("classes:\n  - {name: door, name: fence}\n"),
            "test.yaml:2: key 'classes[0].name' appears twice (first on line 2)");
}

TEST(ConfigReader, WrongTypesNameTheKey) {
  EXPECT_EQ(error_of("alpha: high\n"), "test.yaml:1: key 'alpha': expected a number in [0, 1], got 'high'");
  EXPECT_EQ(error_of("lidar:\n  beams: 2.5\n"),
            "test.yaml:2: key 'lidar.beams': expected an integer (a number >= 1), got '2.5'");
  EXPECT_EQ(error_of("lidar:\n  flip: maybe\n"), "test.yaml:2: key 'lidar.flip': expected true or false, got 'maybe'");
  EXPECT_EQ(error_of("lidar: 3\n"), "test.yaml:1: key 'lidar': expected a mapping of keys, got '3'");
  EXPECT_EQ(error_of("lidar:\n  frame: [a, b]\n"), "test.yaml:2: key 'lidar.frame': expected a string, got a list");
  EXPECT_EQ(error_of("lidar:\n  mount: [1, 2]\n"),
            "test.yaml:2: key 'lidar.mount': expected a list of 3 numbers, got 2");
  EXPECT_EQ(error_of("lidar:\n  mount: [1, x, 2]\n"),
            "test.yaml:2: key 'lidar.mount[1]': expected a finite number, got 'x'");
  EXPECT_EQ(error_of("classes: {name: door}\n"),
            "test.yaml:1: key 'classes': expected a list of mappings, got a mapping");
}

TEST(ConfigReader, OutOfRangeValuesNameTheKey) {
  EXPECT_EQ(error_of("alpha: 1.5\n"), "test.yaml:1: key 'alpha': expected a number in [0, 1], got '1.5'");
  EXPECT_EQ(error_of("lidar:\n  range_max: 0\n"), "test.yaml:2: key 'lidar.range_max': expected a number > 0, got '0'");
  EXPECT_EQ(error_of("lidar:\n  range_max: .nan\n"),
            "test.yaml:2: key 'lidar.range_max': expected a number > 0, got '.nan'");
  EXPECT_EQ(error_of("lidar:\n  range_max: .inf\n"),
            "test.yaml:2: key 'lidar.range_max': expected a number > 0, got '.inf'");
  EXPECT_EQ(error_of("lidar:\n  beams: 99999999999\n"),
            "test.yaml:2: key 'lidar.beams': expected a 32-bit integer, got '99999999999'");
  EXPECT_EQ(error_of("seed: 1e300\n"), "test.yaml:1: key 'seed': expected an integer (a number >= 0), got '1e300'");
  EXPECT_EQ(error_of("mode: fast\n"), "test.yaml:1: key 'mode': expected one of lfm, slfm, slamer, got 'fast'");
  EXPECT_EQ(error_of("classes:\n  - {color: [1, 2, 3]}\n"),
            "test.yaml:2: key 'classes[0].name': missing (this key is required)");
  EXPECT_EQ(error_of("classes:\n  - {name: a, color: [1, 2, 300]}\n"),
            "test.yaml:2: key 'classes[0].color[2]': expected a number in [0, 255], got '300'");
}

TEST(ConfigReader, SyntaxErrorsAndNonMappings) {
  EXPECT_EQ(error_of("alpha: [1, 2\n").rfind("test.yaml:2: YAML syntax error: ", 0), 0u) << error_of("alpha: [1, 2\n");
  EXPECT_EQ(error_of("- a\n- b\n"), "test.yaml: expected a mapping of keys at the top level, got a list");
  EXPECT_EQ(error_of("just text\n"), "test.yaml: expected a mapping of keys at the top level, got 'just text'");
}

TEST(ConfigReader, MissingAndUnreadableFiles) {
  try {
    load_options<TestOptions>("/nonexistent/dir/robot.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/robot.yaml: cannot open: No such file or directory");
  }
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  try {
    load_options<TestOptions>(dir.string());
    FAIL() << "no error for a directory";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), dir.string() + ": cannot read: is a directory");
  }
}

TEST(ConfigReader, LoadsAFileAndKnowsItsDirectory) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "slamer_config_reader_test.yaml";
  {
    std::ofstream out(path);
    out << "alpha: 0.75\n";
  }
  const ConfigReader reader = ConfigReader::from_file(path.string());
  EXPECT_EQ(reader.directory(), path.parent_path().string());
  EXPECT_EQ(reader.resolve_path("maps/../map.yaml"), (path.parent_path() / "map.yaml").string());
  EXPECT_EQ(reader.resolve_path("/abs/map.yaml"), "/abs/map.yaml");
  EXPECT_EQ(reader.resolve_path(""), "");
  EXPECT_EQ(ConfigReader::from_string("", "text").resolve_path("map.yaml"), "map.yaml");
  double alpha = 0.0;
  reader.read("alpha", &alpha, probability());
  EXPECT_DOUBLE_EQ(alpha, 0.75);
  reader.check_all_keys_used();
  std::filesystem::remove(path);
}

TEST(ConfigReader, ParserMessagesWithControlCharactersStayOneLine) {
  // yaml-cpp quotes the offending byte raw; found by the config fuzzer.
  const std::string error = error_of(std::string("\x02\n\0\n", 4));
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_EQ(error.rfind("test.yaml:", 0), 0u) << error;
}

TEST(ConfigReader, ErrorsAreOneLine) {
  const std::string error = error_of("alpha: \"multi\\nline\"\n");
  ASSERT_FALSE(error.empty());
  // The value itself is quoted as given; the message must still be one line.
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace slamer

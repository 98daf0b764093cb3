// The localizer's class_map is checked (issue 11): its keys against the
// recognition classes when the config is read (file and line), its values
// against the map's classes when the node is built on the map.
#include <gtest/gtest.h>

#include "common/config/config_reader.hpp"
#include "localizer/class_map_check.hpp"
#include "localizer/localizer_config.hpp"
#include "localizer/localizer_node.hpp"

namespace slamer {
namespace {

std::string config_error(const std::string& yaml) {
  try {
    parse_options<LocalizerProcessConfig>(yaml, "loc.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

// A 2 m x 2 m room, walls of class `others`, with the given class table.
SemanticMap room(const std::vector<std::string>& class_names) {
  SemanticMap map;
  map.geometry.width = 40;
  map.geometry.height = 40;
  map.geometry.resolution = 0.05;
  map.occupancy.assign(map.geometry.size(), Occupancy::kFree);
  map.labels.assign(map.geometry.size(), -1);
  for (std::size_t i = 0; i < class_names.size(); ++i) {
    map.classes.push_back({class_names[i], {static_cast<uint8_t>(10 * i), 0, 0}});
  }
  const int others = map.class_index("others");
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      if (x == 0 || y == 0 || x == 39 || y == 39) {
        map.occupancy[map.geometry.index(x, y)] = Occupancy::kOccupied;
        map.labels[map.geometry.index(x, y)] = static_cast<int8_t>(others);
      }
    }
  }
  return map;
}

LocalizerOptions small_filter(LocalizerMode mode) {
  LocalizerOptions options;
  options.mode = mode;
  options.particles = 10;
  options.initial_pose = {1.0, 1.0, 0.0};
  return options;
}

const std::vector<std::string> kPaperMapClasses{"door", "glass_door", "fence", "no_entry_line", "others"};

TEST(ClassMapCheck, AKeyTheRecognizerDoesNotEmitIsOneLineWithFileLineAndKey) {
  EXPECT_EQ(config_error("localizer:\n  slamer:\n    class_map:\n      open_door: door\n      opne_door: door\n"),
            "loc.yaml:5: key 'localizer.slamer.class_map.opne_door': 'opne_door' is not a class the recognizer "
            "emits (recognition_classes: open_door, closed_door, open_glass_door, closed_glass_door, fence, "
            "no_entry_line, free_space, others)");
  // A recognizer configured with fewer classes: the default class_map names one it lacks.
  EXPECT_EQ(config_error("localizer:\n  slamer:\n    recognition_classes: [open_door, closed_door, others,\n"
                         "      open_glass_door, closed_glass_door, fence, free_space]\n"),
            "loc.yaml:3: key 'localizer.slamer.recognition_classes': class_map's 'no_entry_line' is not a class "
            "the recognizer emits (recognition_classes: open_door, closed_door, others, open_glass_door, "
            "closed_glass_door, fence, free_space)");
  EXPECT_EQ(config_error("localizer:\n  slamer:\n    recognition_classes: []\n"),
            "loc.yaml:3: key 'localizer.slamer.recognition_classes': the list is empty");
  // Consistent lists load.
  const auto config = parse_options<LocalizerProcessConfig>(
      "localizer:\n  slamer:\n    recognition_classes: [door_open, wall]\n"
      "    class_map: {door_open: door, wall: others}\n    training_prior: {door_open: 0.1, wall: 0.9}\n",
      "loc.yaml");
  EXPECT_EQ(config.localizer.slamer.class_map.size(), 2u);
  EXPECT_EQ(config.localizer.slamer.class_map.at("door_open"), "door");
}

TEST(ClassMapCheck, TheTrainingPriorNamesEveryRecognitionClassOnceWithAProbability) {
  const std::string head =
      "localizer:\n  slamer:\n    recognition_classes: [door_open, wall]\n"
      "    class_map: {door_open: door, wall: others}\n    training_prior:\n";
  EXPECT_EQ(config_error(head + "      door_open: 0.1\n      wal: 0.9\n"),
            "loc.yaml:7: key 'localizer.slamer.training_prior.wal': 'wal' is not a class the recognizer emits "
            "(recognition_classes: door_open, wall)");
  EXPECT_EQ(config_error(head + "      door_open: 0.1\n"),
            "loc.yaml:6: key 'localizer.slamer.training_prior': lacks the recognition class 'wall' (name every one, or "
            "write {} to divide nothing out)");
  EXPECT_EQ(config_error(head + "      door_open: 0\n      wall: 0.9\n"),
            "loc.yaml:6: key 'localizer.slamer.training_prior.door_open': expected a number in [1e-09, 1], got '0'");
  const auto config =
      parse_options<LocalizerProcessConfig>(head + "      door_open: 0.1\n      wall: 0.9\n", "loc.yaml");
  EXPECT_DOUBLE_EQ(config.localizer.slamer.training_prior.at("wall"), 0.9);
  EXPECT_EQ(config_error("localizer:\n  slamer:\n    training_prior_exponent: 1.5\n"),
            "loc.yaml:3: key 'localizer.slamer.training_prior_exponent': expected a number in [0, 1], got '1.5'");
  // With none the recognizer's probabilities are used as they are.
  EXPECT_TRUE(parse_options<LocalizerProcessConfig>("localizer:\n  slamer:\n    training_prior: {}\n", "loc.yaml")
                  .localizer.slamer.training_prior.empty());
}

TEST(ClassMapCheck, AMapClassTheMapDoesNotDeclareIsOneLineNamingTheKey) {
  const LocalizerOptions options = small_filter(LocalizerMode::kSlamer);
  EXPECT_EQ(class_map_problem(options, room(kPaperMapClasses)), "");
  // The case: the map calls the class something else.
  EXPECT_EQ(class_map_problem(options, room({"door", "glass_door", "fence", "no_go", "others"})),
            "key 'localizer.slamer.class_map.no_entry_line': 'no_entry_line' is not a class of the map (it has: "
            "door, glass_door, fence, no_go, others); name one of them, or '' for free space");
  // A purely geometric map: every non-empty entry is a problem, the first in key order named.
  EXPECT_EQ(class_map_problem(options, room({})),
            "key 'localizer.slamer.class_map.closed_door': 'door' is not a class of the map (it has: none); name "
            "one of them, or '' for free space");
  // '' (free space) needs no map class; an entry may map to any class the map has.
  LocalizerOptions custom = options;
  custom.slamer.class_map = {{"free_space", ""}, {"others", "others"}};
  custom.slamer.free_space_class_margins.clear();  // the default's no_entry_line is not in this map either
  EXPECT_EQ(class_map_problem(custom, room({"others"})), "");
  // Options built in code are held to recognition_classes as well.
  custom.slamer.class_map["wall"] = "others";
  EXPECT_EQ(class_map_problem(custom, room({"others"})),
            "key 'localizer.slamer.class_map.wall': 'wall' is not a class the recognizer emits "
            "(recognition_classes: open_door, closed_door, open_glass_door, closed_glass_door, fence, "
            "no_entry_line, free_space, others)");
}

// free_space_class_margins names map classes too: a name the map lacks would
// silently keep free space off nothing; a margin must be positive.
TEST(ClassMapCheck, AFreeSpaceClassMarginForAClassTheMapLacksIsOneLineNamingTheKey) {
  LocalizerOptions options = small_filter(LocalizerMode::kSlamer);
  options.slamer.free_space_class_margins = {{"no_entry_line", 0.7}};
  EXPECT_EQ(class_map_problem(options, room(kPaperMapClasses)), "");
  options.slamer.free_space_class_margins = {{"wall", 0.7}};
  EXPECT_EQ(class_map_problem(options, room(kPaperMapClasses)),
            "key 'localizer.slamer.free_space_class_margins.wall': 'wall' is not a class of the map (it has: door, "
            "glass_door, fence, no_entry_line, others)");
  const auto config = parse_options<LocalizerProcessConfig>(
      "localizer:\n  slamer:\n    free_space_class_margins: {no_entry_line: 0.7, door: 0.3}\n"
      "    spatial_line_ends: left_out\n",
      "loc.yaml");
  EXPECT_EQ(config.localizer.slamer.free_space_class_margins,
            (std::map<std::string, double>{{"door", 0.3}, {"no_entry_line", 0.7}}));
  EXPECT_EQ(config.localizer.slamer.spatial_line_ends, SpatialLineEnds::kLeftOut);
  EXPECT_NE(config_error("localizer:\n  slamer:\n    free_space_class_margins: {no_entry_line: 0}\n")
                .find("free_space_class_margins.no_entry_line"),
            std::string::npos);
  EXPECT_NE(config_error("localizer:\n  slamer:\n    spatial_line_ends: sometimes\n").find("spatial_line_ends"),
            std::string::npos);
}

TEST(ClassMapCheck, OnlyTheModesThatUseClassesAreChecked) {
  const SemanticMap geometric = room({"others"});
  EXPECT_EQ(class_map_problem(small_filter(LocalizerMode::kLfm), geometric), "");
  EXPECT_NE(class_map_problem(small_filter(LocalizerMode::kSlfm), geometric), "");
  EXPECT_NE(class_map_problem(small_filter(LocalizerMode::kSlamer), geometric), "");
}

TEST(ClassMapCheck, TheNodeRefusesToStartOnAMapWithoutTheClasses) {
  const Pose2 mount{0.2, 0.0, 0.0};
  EXPECT_NO_THROW(LocalizerNode(room(kPaperMapClasses), small_filter(LocalizerMode::kSlamer), mount));
  EXPECT_NO_THROW(LocalizerNode(room({"others"}), small_filter(LocalizerMode::kLfm), mount));
  try {
    LocalizerNode node(room({"door", "glass_door", "fence", "do_not_enter_line", "others"}),
                       small_filter(LocalizerMode::kSlamer), mount);
    ADD_FAILURE() << "built on a map without no_entry_line";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("key 'localizer.slamer.class_map.no_entry_line': ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace slamer

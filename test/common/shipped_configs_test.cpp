// Every YAML file shipped in config/ loads with the loader of the program it
// belongs to, and no file is shipped without a loader listed here.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "common/config/config_reader.hpp"
#include "tools/status/status_table.hpp"

namespace slamer {
namespace {

const std::map<std::string, std::function<void(const std::string&)>>& loaders() {
  static const std::map<std::string, std::function<void(const std::string&)>> table = {
      {"slamer-status.yaml", [](const std::string& path) { load_options<StatusProcessConfig>(path); }},
  };
  return table;
}

TEST(ShippedConfigs, EveryFileLoadsWithItsProgramsLoader) {
  const std::filesystem::path dir = std::filesystem::path(SLAMER_SOURCE_DIR) / "config";
  std::set<std::string> seen;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") {
      continue;
    }
    const std::string name = std::filesystem::relative(entry.path(), dir).string();
    seen.insert(name);
    const auto loader = loaders().find(name);
    ASSERT_NE(loader, loaders().end()) << "config/" << name << " has no loader in " << __FILE__;
    EXPECT_NO_THROW(loader->second(entry.path().string())) << "config/" << name;
    try {
      loader->second(entry.path().string());
    } catch (const ConfigError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  for (const auto& [name, loader] : loaders()) {
    EXPECT_TRUE(seen.count(name) != 0) << "the loader table names config/" << name << ", which does not exist";
  }
}

}  // namespace
}  // namespace slamer

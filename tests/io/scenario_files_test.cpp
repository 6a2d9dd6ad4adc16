// Every bundled scenario (scenarios/**/*.json except scenarios/schema/) loads without a
// diagnostic, reachability included. Passes trivially while there are none.
#include <gtest/gtest.h>

#include <filesystem>

#include "throng/io/scenario_loader.hpp"

namespace fs = std::filesystem;

TEST(ScenarioFiles, EveryBundledScenarioValidates) {
  const fs::path root = fs::path(THRONG_SOURCE_DIR) / "scenarios";
  ASSERT_TRUE(fs::is_directory(root)) << root << " missing: the bundled scenarios are part of the source tree";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    const std::string top = fs::relative(entry.path(), root).begin()->string();
    if (top == "schema" || top == "crowds") continue;  // crowd files load through a scenario's timeline
    files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5U) << "bundled scenarios found under " << root;
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    auto r = throng::io::loadScenarioFile(file.string());
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : throng::core::formatAll(r.errors()));
  }
  RecordProperty("scenarios", static_cast<int>(files.size()));
}

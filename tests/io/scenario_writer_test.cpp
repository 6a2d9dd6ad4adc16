// The scenario writer (scenario_writer.cpp): JSON formatted for diffs (flat arrays on one line,
// key order kept, bad UTF-8 replaced) and atomic writes that never overwrite without being asked.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "throng/io/scenario_writer.hpp"

namespace throng::io {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ScenarioWriter, FormatsForDiffs) {
  const auto v = nlohmann::ordered_json::parse(
      R"({"z": 1, "a": [[0, 0], [1.5, 2]], "e": [], "o": {}, "w": [{"line": [[0, 0], [1, 0]], "s": "x\u00e9"}], "f": [true, null]})");
  EXPECT_EQ(formatJsonForDiffs(v),
            "{\n"
            "  \"z\": 1,\n"
            "  \"a\": [\n"
            "    [0, 0],\n"
            "    [1.5, 2]\n"
            "  ],\n"
            "  \"e\": [],\n"
            "  \"o\": {},\n"
            "  \"w\": [\n"
            "    {\n"
            "      \"line\": [\n"
            "        [0, 0],\n"
            "        [1, 0]\n"
            "      ],\n"
            "      \"s\": \"x\u00e9\"\n"
            "    }\n"
            "  ],\n"
            "  \"f\": [true, null]\n"
            "}\n");
  // What it prints parses back to the same value.
  EXPECT_EQ(nlohmann::ordered_json::parse(formatJsonForDiffs(v)), v);
  EXPECT_EQ(formatJsonForDiffs(nlohmann::ordered_json(std::string("a\xff"))), "\"a\xef\xbf\xbd\"\n");
}

TEST(ScenarioWriter, WritesAtomicallyAndKeepsExistingFiles) {
  const fs::path dir = fs::temp_directory_path() / ("throng-writer-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "s.json").string();
  ASSERT_TRUE(writeFileAtomically(path, "one\n", false).ok());
  EXPECT_EQ(slurp(path), "one\n");
  const auto refused = writeFileAtomically(path, "two\n", false);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.errors()[0].source, path);
  EXPECT_EQ(refused.errors()[0].what, "file exists");
  EXPECT_EQ(slurp(path), "one\n");
  ASSERT_TRUE(writeFileAtomically(path, "two\n", true).ok());
  EXPECT_EQ(slurp(path), "two\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);  // no temporary file left
  const auto missing = writeFileAtomically((dir / "no" / "s.json").string(), "x", false);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.errors()[0].what.find("cannot create a temporary file"), std::string::npos) << missing.errors()[0].format();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace throng::io

// Tests for libs/io/src/confined_path.cpp and its callers: every path a scenario or a glTF world
// names — an action point's clip, a timeline crowd, the social databases, the motions directory —
// is read only from the naming file's directory and below. "..", absolute paths and symbolic links
// leading out are refused with one located message, and the refused file is never opened: no byte
// of it (here a line like /etc/shadow's) appears in any diagnostic.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "confined_path.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/io/world_file.hpp"

namespace {

namespace fs = std::filesystem;
using namespace throng;

/// What the file outside holds: it must never be echoed.
const std::string kSecret = "root:$6$SECRET-HASH-7f3a:19000:0:99999:7:::";

const char* kScenario = R"({
  "format": "throng/1",
  "walkable": [ [[0,0],[20,0],[20,10],[0,10]] ],
  "points": [
    {"id": "exit", "kind": "exit", "position": [19, 5]},
    {"id": "statue", "kind": "action", "position": [10, 5], "orientation": [0, 1], "clip": "CLIP"}
  ],
  "populations": [
    {"id": "visitors", "groups": 2, "spawn": {"polygon": [[1,1],[4,1],[4,9],[1,9]]}, "goals": ["statue", "exit"]}
  ]EXTRA
}
)";

std::string scenario(const std::string& clip, const std::string& extra = "") {
  std::string s = kScenario;
  s.replace(s.find("CLIP"), 4, clip);
  s.replace(s.find("EXTRA"), 5, extra);
  return s;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// <scratch>/world/ holds the scenario and motions/look.bvh; <scratch>/outside/ the secret files
/// (as a clip, a crowd file and a database would be named).
class ConfinedPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::path(THRONG_BINARY_DIR) / "tests" / "io" / "confined" / info->name();
    fs::remove_all(root_);
    fs::create_directories(root_ / "world" / "motions");
    fs::copy_file(fs::path(THRONG_SOURCE_DIR) / "scenarios" / "motions" / "look.bvh",
                  root_ / "world" / "motions" / "look.bvh");
    for (const char* name : {"secret.bvh", "secret.json", "look.bvh"}) write(root_ / "outside" / name, kSecret + "\n");
  }
  void TearDown() override { fs::remove_all(root_); }

  /// Every diagnostic of loading `text` as world/t.json, formatted; "" when it loads.
  std::string errorsOf(const std::string& text) const {
    write(root_ / "world" / "t.json", text);
    const auto r = io::loadScenarioFile((root_ / "world" / "t.json").string());
    return r.ok() ? "" : core::formatAll(r.errors());
  }
  static void expectRefused(const std::string& text, const std::string& pointer, const std::string& why) {
    EXPECT_NE(text.find(pointer + ": "), std::string::npos) << text;
    EXPECT_NE(text.find(why), std::string::npos) << text;
    EXPECT_NE(text.find("expected "), std::string::npos) << text;
    EXPECT_EQ(text.find("SECRET"), std::string::npos) << "the outside file's content was echoed:\n" << text;
    EXPECT_EQ(text.find("root:"), std::string::npos) << text;
  }

  fs::path root_;
};

TEST_F(ConfinedPaths, AClipInsideLoadsEvenThroughDotDotThatStaysInside) {
  EXPECT_EQ(errorsOf(scenario("motions/look.bvh")), "");
  EXPECT_EQ(errorsOf(scenario("motions/../motions/./look.bvh")), "");
}

TEST_F(ConfinedPaths, AClipOutsideIsRefusedAtItsPointer) {
  const std::string text = errorsOf(scenario("../outside/secret.bvh"));
  expectRefused(text, "t.json:6:92 /points/1/clip", "clip \"../outside/secret.bvh\" leads out of the directory of t.json");
  // Absolute paths are refused by the parser already (before any file is touched).
  expectRefused(errorsOf(scenario((root_ / "outside" / "secret.bvh").string())), "/points/1/clip", "absolute path");
}

TEST_F(ConfinedPaths, ASymbolicLinkLeadingOutIsRefused) {
  fs::create_directory_symlink(root_ / "outside", root_ / "world" / "shared");
  const std::string text = errorsOf(scenario("shared/secret.bvh"));
  expectRefused(text, "/points/1/clip", "\"shared/secret.bvh\" leads out of the directory of t.json through a symbolic link");
  // A link that stays inside is fine.
  fs::create_directory_symlink(root_ / "world" / "motions", root_ / "world" / "clips");
  EXPECT_EQ(errorsOf(scenario("clips/look.bvh")), "");
}

TEST_F(ConfinedPaths, ATimelineCrowdOutsideIsRefused) {
  write(root_ / "outside" / "crowd.json",
        R"({"format": "throng-crowd/1", "id": "c", "populations": [{"id": "p", "groups": 1, "spawn": {"point": "exit"}, "goals": ["exit"]}]})");
  const std::string text = errorsOf(scenario("motions/look.bvh", R"(,
  "timeline": [{"time": 5, "insert": "../outside/crowd.json"}])"));
  expectRefused(text, "/timeline/0/insert", "crowd file \"../outside/crowd.json\" leads out of the directory of t.json");
}

TEST_F(ConfinedPaths, SocialDatabasesAndTheMotionsDirectoryOutsideAreRefused) {
  expectRefused(errorsOf(scenario("motions/look.bvh", R"(,
  "social": {"microBehaviours": "../outside/secret.json"})")),
                "/social/microBehaviours", "\"../outside/secret.json\" leads out of the directory of t.json");
  expectRefused(errorsOf(scenario("motions/look.bvh", R"(,
  "social": {"macroPlans": "motions/../../outside/secret.json"})")),
                "/social/macroPlans", "\"motions/../../outside/secret.json\" leads out of the directory of t.json");
  expectRefused(errorsOf(scenario("motions/look.bvh", R"(,
  "social": {"motions": "../outside"})")),
                "/social/motions", "\"../outside\" leads out of the directory of t.json");
}

TEST_F(ConfinedPaths, AGltfWorldCannotNameFilesOutsideItsDirectory) {
  // The gallery, with the bench playing a clip and the scene naming a database, both outside.
  std::ifstream in(std::string(THRONG_SOURCE_DIR) + "/scenarios/gallery.gltf");
  nlohmann::json g = nlohmann::json::parse(in);
  for (auto& n : g["nodes"]) {
    if (n.value("name", "") == "action:bench") n["extras"]["throng"]["clip"] = "../outside/secret.bvh";
  }
  write(root_ / "world" / "world.gltf", g.dump());
  auto r = io::loadScenarioFile((root_ / "world" / "world.gltf").string());
  ASSERT_FALSE(r.ok());
  std::string text = core::formatAll(r.errors());
  expectRefused(text, "/extras/throng/clip", "clip \"../outside/secret.bvh\" leads out of the directory of world.gltf");
  EXPECT_NE(text.find("\"action:bench\""), std::string::npos) << text;

  g["scenes"][0]["extras"]["throng"]["social"] = {{"microBehaviours", "../outside/secret.json"}};
  for (auto& n : g["nodes"]) {
    if (n.value("name", "") == "action:bench") n["extras"]["throng"].erase("clip");
  }
  write(root_ / "world" / "world.gltf", g.dump());
  r = io::loadScenarioFile((root_ / "world" / "world.gltf").string());
  ASSERT_FALSE(r.ok());
  text = core::formatAll(r.errors());
  expectRefused(text, "scene 0 /extras/throng/social/microBehaviours",
                "\"../outside/secret.json\" leads out of the directory of world.gltf");
}

TEST(ConfinedPath, OneRuleForEveryKind) {
  namespace d = io::detail;
  const fs::path dir = fs::path(THRONG_SOURCE_DIR) / "scenarios";
  EXPECT_TRUE(d::confinePath(dir, "motions/look.bvh", "x").ok());
  EXPECT_EQ(d::confinePath(dir, "motions/look.bvh", "x").path, (dir / "motions/look.bvh").lexically_normal());
  EXPECT_TRUE(d::confinePath(dir, "not/there/yet.json", "x").ok());  // missing files are the caller's message
  EXPECT_TRUE(d::confinePath(dir, "a/../b.json", "x").ok());
  EXPECT_TRUE(d::confinePath(dir, ".", "x").ok());
  for (const std::string bad : {"..", "../x", "a/../../x", "./../x", "/etc/shadow", "\\\\server\\x", "C:x", ""}) {
    const d::ConfinedPath c = d::confinePath(dir, bad, "x");
    EXPECT_FALSE(c.ok()) << bad;
    EXPECT_TRUE(c.path.empty()) << bad;
  }
  // The working directory when the naming file has none.
  EXPECT_TRUE(d::confinePath("", "file.json", "x").ok());
  EXPECT_FALSE(d::confinePath("", "../file.json", "x").ok());
  // The predicate glTF buffers use.
  const fs::path root = d::canonicalDirectory(dir);
  EXPECT_TRUE(d::insideDirectory(root, dir / "motions" / "look.bvh"));
  EXPECT_FALSE(d::insideDirectory(root, dir / ".." / "README.md"));
  EXPECT_FALSE(d::insideDirectory(fs::path(), dir / "motions" / "look.bvh"));
}

}  // namespace

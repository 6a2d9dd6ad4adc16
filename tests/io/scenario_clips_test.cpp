// Tests for libs/io/src/scenario_clips.cpp (and the "clip" key of scenario_parser.cpp): an action
// point's motion clip is loaded relative to the scenario, gives the point its duration and action
// name, and every way it can be wrong is one located diagnostic (plus the clip's own).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "throng/io/scenario_loader.hpp"
#include "scenario_test_util.hpp"

using namespace throng;
using throng::io::test::posOf;
using throng::io::test::contains;
namespace fs = std::filesystem;

namespace {

const char* kMuseum = R"({
  "format": "throng/1",
  "walkable": [ [[0,0],[20,0],[20,10],[0,10]] ],
  "points": [
    {"id": "exit", "kind": "exit", "position": [19, 5]},
    {"id": "statue", "kind": "action", "position": [10, 5], "orientation": [0, 1], "clip": "motions/look.bvh"}
  ],
  "populations": [
    {"id": "visitors", "groups": 2, "spawn": {"polygon": [[1,1],[4,1],[4,9],[1,9]]}, "goals": ["statue", "exit"]}
  ]
}
)";

const char* kBadClip = "HIERARCHY\nROOT r\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Xrotation\n  JOINT j\n  {\n    OFSET 0 0 0\n  }\n}\n";

std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

/// A fresh directory holding motions/look.bvh (the bundled clip) for one test.
fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(THRONG_BINARY_DIR) / "tests" / "io" / "clips" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir / "motions");
  fs::copy_file(fs::path(THRONG_SOURCE_DIR) / "scenarios" / "motions" / "look.bvh", dir / "motions" / "look.bvh");
  return dir;
}

core::Result<io::LoadedScenario> loadIn(const fs::path& dir, const std::string& text) {
  write(dir / "museum.json", text);
  return io::loadScenarioFile((dir / "museum.json").string());
}

}  // namespace

TEST(ScenarioClips, DurationAndActionComeFromTheClip) {
  const fs::path dir = scratch();
  auto r = loadIn(dir, kMuseum);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::PointDesc& statue = r->desc.points[1];
  EXPECT_EQ(statue.clip, "motions/look.bvh");
  EXPECT_EQ(statue.action, "look");
  EXPECT_FLOAT_EQ(statue.actionDuration, 4.0f);
  EXPECT_TRUE(statue.stop);
  EXPECT_TRUE(r->desc.points[0].clip.empty());
  ASSERT_EQ(r->clips.size(), 1u);
  const auto& clip = r->clips.at("motions/look.bvh");
  ASSERT_NE(clip, nullptr);
  EXPECT_EQ(clip->name, "look");
  EXPECT_DOUBLE_EQ(clip->duration(), 4.0);
}

TEST(ScenarioClips, ExplicitDurationAndActionWin) {
  const fs::path dir = scratch();
  auto r = loadIn(dir, edit(kMuseum, "\"clip\"", "\"duration\": 1.5, \"action\": \"gaze\", \"clip\""));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_FLOAT_EQ(r->desc.points[1].actionDuration, 1.5f);
  EXPECT_EQ(r->desc.points[1].action, "gaze");
  EXPECT_EQ(r->clips.count("motions/look.bvh"), 1u);  // still loaded for the viewer
}

TEST(ScenarioClips, TextIsResolvedAgainstTheSourcesDirectory) {
  const fs::path dir = scratch();
  auto r = io::parseScenario(kMuseum, (dir / "not-on-disk.json").string(), io::LoadOptions{false});
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_FLOAT_EQ(r->desc.points[1].actionDuration, 4.0f);

  // The bundled clips resolve for scenarios kept in scenarios/.
  const std::string bundled = edit(kMuseum, "motions/look.bvh", "motions/walk.bvh");
  auto b = io::parseScenario(bundled, std::string(THRONG_SOURCE_DIR) + "/scenarios/inline.json", io::LoadOptions{false});
  ASSERT_TRUE(b.ok()) << core::formatAll(b.errors());
  EXPECT_NEAR(b->desc.points[1].actionDuration, 1.12f, 1e-6f);
  EXPECT_EQ(b->desc.points[1].action, "walk");
}

TEST(ScenarioClips, MissingClipSuggestsTheClosestFile) {
  const fs::path dir = scratch();
  const std::string text = edit(kMuseum, "motions/look.bvh", "motions/lok.bvh");
  auto r = loadIn(dir, text);
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors().size(), 1u) << core::formatAll(r.errors());
  const core::Diagnostic& d = r.errors()[0];
  const auto [line, col] = posOf(text, "\"motions/lok.bvh\"");
  EXPECT_EQ(d.source, (dir / "museum.json").string());
  EXPECT_EQ(d.line, line);
  EXPECT_EQ(d.column, col);
  EXPECT_EQ(d.pointer, "/points/1/clip");
  EXPECT_EQ(d.format(), (dir / "museum.json").string() + ":" + std::to_string(line) + ":" + std::to_string(col) +
                           " /points/1/clip: cannot read \"motions/lok.bvh\": no such "
                                                          "file; expected a BVH file path relative to the scenario (did "
                                                          "you mean \"motions/look.bvh\"?)");

  // A directory named as a clip is not readable either; nothing close: no hint.
  auto dirClip = loadIn(dir, edit(kMuseum, "motions/look.bvh", "motions"));
  ASSERT_FALSE(dirClip.ok());
  EXPECT_EQ(dirClip.errors()[0].what, "cannot read \"motions\": not a regular file");
  auto far = loadIn(dir, edit(kMuseum, "motions/look.bvh", "dance/tango.bvh"));
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(far.errors()[0].hint, "");
}

TEST(ScenarioClips, BadClipKeepsItsOwnDiagnostics) {
  const fs::path dir = scratch();
  write(dir / "motions" / "bad.bvh", kBadClip);
  // Two points use the bad clip: its own diagnostic once, one at each point.
  std::string text = edit(kMuseum, "motions/look.bvh", "motions/bad.bvh");
  text = edit(text, "{\"id\": \"exit\",",
              "{\"id\": \"bench\", \"kind\": \"action\", \"position\": [12, 5], \"clip\": \"motions/bad.bvh\"},\n"
              "    {\"id\": \"exit\",");
  auto r = loadIn(dir, text);
  ASSERT_FALSE(r.ok());
  const auto& ds = r.errors();
  ASSERT_EQ(ds.size(), 3u) << core::formatAll(ds);
  EXPECT_EQ(ds[0].pointer, "/points/0/clip");
  EXPECT_EQ(ds[1].pointer, "/points/2/clip");
  EXPECT_EQ(ds[0].expected, "a valid BVH file");
  EXPECT_NE(ds[0].what.find("motion clip \"motions/bad.bvh\" is not valid BVH (1 problem"), std::string::npos)
      << ds[0].format();
  EXPECT_EQ(ds[2].source, (dir / "motions" / "bad.bvh").string());
  EXPECT_EQ(ds[2].line, 8);
  EXPECT_EQ(ds[2].column, 5);
  EXPECT_EQ(ds[2].what, "found \"OFSET\"");
}

TEST(ScenarioClips, ClipIsCheckedLikeTheOtherActionKeys) {
  const fs::path dir = scratch();
  auto onExit = loadIn(dir, edit(kMuseum, "\"position\": [19, 5]}", "\"position\": [19, 5], \"clip\": \"motions/look.bvh\"}"));
  ASSERT_FALSE(onExit.ok());
  EXPECT_EQ(onExit.errors()[0].pointer, "/points/0/clip");
  EXPECT_EQ(onExit.errors()[0].what, "\"clip\" only applies to action points");

  for (const char* bad : {"/etc/look.bvh", ""}) {
    auto r = loadIn(dir, edit(kMuseum, "\"motions/look.bvh\"", std::string("\"") + bad + "\""));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.errors()[0].pointer, "/points/1/clip");
    EXPECT_EQ(r.errors()[0].expected, "a BVH file path relative to the scenario (\"motions/look.bvh\")");
  }
  auto number = loadIn(dir, edit(kMuseum, "\"motions/look.bvh\"", "4.5"));
  ASSERT_FALSE(number.ok());
  EXPECT_EQ(number.errors()[0].what, "wrong type: a number");

  auto typo = loadIn(dir, edit(kMuseum, "\"clip\"", "\"clpi\""));
  ASSERT_FALSE(typo.ok());
  EXPECT_EQ(typo.errors()[0].hint, "did you mean \"clip\"?");
}

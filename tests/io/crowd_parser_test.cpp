// io::parseCrowd and the scenario timeline: crowd files parsed with the scenario's diagnostics
// (file:line:column, pointer, expected, "did you mean") and validated against the world they join.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "scenario_test_util.hpp"
#include "temp_dir.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::io {
namespace {

using test::at;
using test::expectAt;

const char* kWorld = R"({
  "format": "throng/1",
  "walkable": [[[0, 0], [30, 0], [30, 10], [0, 10]]],
  "obstacles": [[[14, 0], [16, 0], [16, 10], [14, 10]], [[25, 0], [26, 0], [26, 10], [25, 10]]],
  "points": [
    {"id": "left", "kind": "interest", "position": [3, 5], "radius": 1.5},
    {"id": "look", "kind": "action", "position": [10, 5], "radius": 1, "action": "look", "duration": 3},
    {"id": "right", "kind": "interest", "position": [20, 5], "radius": 1.5}
  ],
  "populations": [
    {"id": "walkers", "groups": 2, "spawn": {"polygon": [[1, 1], [8, 1], [8, 9], [1, 9]]}, "goals": ["left"], "radius": 0.25}
  ]
})";

const LoadedScenario& world() {
  static const LoadedScenario w = [] {
    auto r = parseScenario(kWorld, "world.json");
    EXPECT_TRUE(r.ok()) << core::formatAll(r.errors());
    return std::move(r).value();
  }();
  return w;
}

core::Result<sim::CrowdDesc> crowd(const std::string& text) {
  CrowdOptions options;
  options.navmesh = world().navmesh;
  return parseCrowd(text, "c.json", world().desc, options);
}

core::Diagnostics errorsOf(const std::string& text) {
  auto r = crowd(text);
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? core::Diagnostics{} : r.errors();
}

const std::string kGood = R"({
  "format": "throng-crowd/1",
  "id": "tour",
  "points": [{"id": "meet", "kind": "interest", "position": [6, 8], "radius": 1}],
  "populations": [
    {"id": "tourists", "groups": 1, "size": 4, "spawn": {"point": "left"}, "goals": ["look", "meet"], "radius": 0.2}
  ]
})";

TEST(CrowdParser, AGoodCrowdResolvesWorldAndOwnPoints) {
  auto r = crowd(kGood);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::CrowdDesc& c = r.value();
  EXPECT_EQ(c.id, "tour");
  EXPECT_EQ(c.basePoints, 3u);
  EXPECT_EQ(c.basePopulations, 1u);
  ASSERT_EQ(c.points.size(), 1u);
  EXPECT_EQ(c.points[0].id, "meet");
  ASSERT_EQ(c.populations.size(), 1u);
  EXPECT_EQ(c.populations[0].goals, (std::vector<std::uint32_t>{1, 3}));
  EXPECT_EQ(c.populations[0].spawn.point, 0u);
  EXPECT_EQ(c.maxAgents(), 4u);
}

TEST(CrowdParser, BadKeysAndUnknownPointsAreReportedWhereTheyAre) {
  const std::string text = R"({
  "format": "throng-crowd/1",
  "id": "tour",
  "popluations": [],
  "populations": [
    {"id": "tourists", "grups": 1, "spawn": {"point": "lefft"}, "goals": ["look", "mete"]}
  ]
})";
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 4u) << core::formatAll(ds);
  const auto d0 = at(ds, "/popluations");
  EXPECT_EQ(d0.what, "unknown key \"popluations\" in the crowd file");
  EXPECT_EQ(d0.hint, "did you mean \"populations\"?");
  expectAt(d0, text, "\"popluations\"", 0, "c.json");
  const auto d1 = at(ds, "/populations/0/grups");
  EXPECT_EQ(d1.hint, "did you mean \"groups\"?");
  const auto d2 = at(ds, "/populations/0/spawn/point");
  EXPECT_EQ(d2.what, "unknown point \"lefft\"");
  EXPECT_EQ(d2.hint, "did you mean \"left\"?");
  expectAt(d2, text, "\"lefft\"", 0, "c.json");
  const auto d3 = at(ds, "/populations/0/goals/1");
  EXPECT_EQ(d3.what, "unknown point \"mete\"");
}

TEST(CrowdParser, ClashesWithTheWorldAreReported) {
  const std::string text = R"({
  "format": "throng-crowd/1",
  "id": "tour",
  "points": [{"id": "right", "kind": "interest", "position": [6, 8]}],
  "populations": [{"id": "walkers", "spawn": {"point": "left"}}]
})";
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 2u) << core::formatAll(ds);
  EXPECT_EQ(at(ds, "/points/0/id").what, "point id \"right\" is already a point of the world");
  EXPECT_EQ(at(ds, "/populations/0/id").what, "population id \"walkers\" is already a population of the world");
  CrowdOptions options;
  options.takenCrowdIds = {"tour"};
  auto r = parseCrowd(kGood, "c.json", world().desc, options);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors().front().what, "crowd id \"tour\" is already taken");
  expectAt(r.errors().front(), kGood, "\"tour\"", 0, "c.json");
}

TEST(CrowdParser, LimitsAndTheWorldsRadiusAndClipsAreEnforced) {
  const std::string text = R"({
  "format": "throng-crowd/1",
  "id": "mob",
  "points": [{"id": "dance", "kind": "action", "position": [6, 8], "action": "dnace", "clip": "motions/dance.bvh"}],
  "populations": [
    {"id": "mob", "groups": 2001, "size": 5, "spawn": {"polygon": [[1, 1], [8, 1], [8, 9], [1, 9]]}, "radius": 0.3}
  ]
})";
  const auto ds = errorsOf(text);
  EXPECT_EQ(at(ds, "/points/0/clip").what, "a crowd file cannot load motion clips into a running world");
  const auto action = at(ds, "/points/0/action");
  EXPECT_EQ(action.what, "action \"dnace\" has no clip in the world");
  EXPECT_EQ(action.expected, "an action the world's action points play: \"look\"");
  const auto radius = at(ds, "/populations/0/radius");
  EXPECT_EQ(radius.what, "body radius 0.3 m is larger than the world's navmesh allows for this model, 0.25 m");
  const auto limit = at(ds, "/populations");
  EXPECT_EQ(limit.what, "the crowd may spawn 10005 agents (groups × largest group size, summed)");
  EXPECT_EQ(limit.expected, "at most 10000 agents per crowd insertion");
}

TEST(CrowdParser, SpawnsOutsideOrUnreachableAreReported) {
  const std::string text = R"({
  "format": "throng-crowd/1",
  "id": "lost",
  "points": [{"id": "void", "kind": "interest", "position": [60, 60], "radius": 1}],
  "populations": [
    {"id": "outside", "spawn": {"position": [40, 5]}},
    {"id": "walled", "spawn": {"point": "right"}, "goals": ["left"]}
  ]
})";
  const auto ds = errorsOf(text);
  EXPECT_EQ(at(ds, "/populations/0/spawn/position").what, "spawn position (40, 5) is outside the walkable area");
  // Reachability runs once the rest is clean.
  const std::string walled = R"({
  "format": "throng-crowd/1",
  "id": "lost",
  "points": [{"id": "void", "kind": "interest", "position": [60, 60], "radius": 1}],
  "populations": [{"id": "walled", "spawn": {"point": "right"}, "goals": ["left"]}]
})";
  const auto ws = errorsOf(walled);
  ASSERT_EQ(ws.size(), 2u) << core::formatAll(ws);
  EXPECT_EQ(at(ws, "/points/0").what, "point \"void\" at (60, 60) lies outside the walkable area (no walkable ground within 2 m)");
  EXPECT_EQ(at(ws, "/populations/0/goals/0").what, "point \"left\" cannot be reached from the spawn area of population \"walled\"");
}

TEST(CrowdParser, FormatAndSyntaxErrors) {
  auto ds = errorsOf(R"({"format": "throng/1", "id": "x", "populations": []})");
  ASSERT_EQ(ds.size(), 2u) << core::formatAll(ds);
  EXPECT_EQ(at(ds, "/format").what, "unsupported format \"throng/1\"");
  EXPECT_EQ(at(ds, "/format").hint, "this is a scenario's format; a crowd file says \"throng-crowd/1\"");
  EXPECT_EQ(at(ds, "/populations").what, "no population");
  ds = errorsOf("{\"format\": \"throng-crowd/1\",\n  \"id\": }");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 2);
}

TEST(CrowdParser, TheWorldOverloadSeesInsertedCrowds) {
  auto w = sim::World::create(world().desc, world().navmesh);
  ASSERT_TRUE(w.ok());
  auto c = parseCrowd(kGood, "c.json", *w.value());
  ASSERT_TRUE(c.ok()) << core::formatAll(c.errors());
  ASSERT_TRUE(w.value()->insertCrowd(c.value()).ok());
  core::TaskSystem tasks(1);
  w.value()->step(tasks);
  auto again = parseCrowd(kGood, "c.json", *w.value());
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(at(again.errors(), "/id").what, "crowd id \"tour\" is already taken");
  EXPECT_EQ(at(again.errors(), "/points/0/id").what, "point id \"meet\" is already a point of the world");
}

TEST(ScenarioTimeline, CrowdFilesAreLoadedAndChecked) {
  throng::test::TempDir dir;
  const std::filesystem::path root = dir.path();
  std::filesystem::create_directories(root / "crowds");
  std::ofstream(root / "crowds" / "tour.json") << kGood;
  std::ofstream(root / "crowds" / "bad.json") << "{\n  \"format\": \"throng-crowd/1\",\n  \"id\": \"bad\",\n  \"populations\": [{\"id\": \"b\", \"spawn\": {\"point\": \"nowhere\"}}]\n}";
  std::string scenario = kWorld;
  scenario.insert(scenario.rfind('}'), R"(,
  "timeline": [
    {"time": 5, "insert": "crowds/tour.json"},
    {"time": 9, "remove": "tour"}
  ])");
  std::ofstream(root / "s.json") << scenario;
  auto r = loadScenarioFile((root / "s.json").string());
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const auto& timeline = r.value().desc.timeline;
  ASSERT_EQ(timeline.size(), 2u);
  EXPECT_EQ(timeline[0].crowd.id, "tour");
  EXPECT_EQ(timeline[0].crowd.populations[0].goals, (std::vector<std::uint32_t>{1, 3}));
  EXPECT_EQ(timeline[1].action, sim::TimelineAction::Remove);

  std::string bad = kWorld;
  bad.insert(bad.rfind('}'), R"(,
  "timeline": [
    {"time": 5, "insert": "crowds/bad.json"},
    {"time": 4, "remove": "tuor"},
    {"time": 6, "insert": "crowds/missing.json"},
    {"time": 7, "remove": "tuor", "insert": "x.json"},
    {"tme": 8, "remove": "tour"}
  ])");
  std::ofstream(root / "bad.json") << bad;
  auto b = loadScenarioFile((root / "bad.json").string());
  ASSERT_FALSE(b.ok());
  const auto& ds = b.errors();
  EXPECT_EQ(at(ds, "/timeline/1/time").what, "time 4 s is before the previous entry's 5 s");
  EXPECT_EQ(at(ds, "/timeline/3").what, "entry has both \"insert\" and \"remove\"");
  EXPECT_EQ(at(ds, "/timeline/4/tme").hint, "did you mean \"time\"?");
  // Structure problems first: the crowd files are read only for a clean scenario.
  std::string bad2 = kWorld;
  bad2.insert(bad2.rfind('}'), R"(,
  "timeline": [
    {"time": 5, "insert": "crowds/bad.json"},
    {"time": 6, "insert": "crowds/missing.json"},
    {"time": 7, "remove": "tuor"}
  ])");
  std::ofstream(root / "bad2.json") << bad2;
  auto b2 = loadScenarioFile((root / "bad2.json").string());
  ASSERT_FALSE(b2.ok());
  const auto& es = b2.errors();
  ASSERT_EQ(es.size(), 3u) << core::formatAll(es);
  const auto inFile = at(es, "/populations/0/spawn/point");
  EXPECT_EQ(inFile.source, (root / "crowds" / "bad.json").string());
  EXPECT_EQ(inFile.line, 4);
  EXPECT_EQ(inFile.what, "unknown point \"nowhere\"");
  EXPECT_TRUE(test::contains(at(es, "/timeline/1/insert").what, "cannot load crowd file \"crowds/missing.json\""));
  EXPECT_EQ(at(es, "/timeline/2/remove").what, "no crowd \"tuor\" is inserted before");
}

}  // namespace
}  // namespace throng::io

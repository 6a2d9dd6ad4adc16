// Tests for the diagnostics of libs/io/src/{json_document,scenario_parser,scenario_validator}.cpp:
// one test per class of error, each asserting file:line:col, JSON pointer, what and expected.
#include <gtest/gtest.h>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

}  // namespace

TEST(ScenarioErrors, JsonSyntaxErrorHasLineAndColumn) {
  const std::string text = edit(kBottleneck, "\"seed\": 7,", "\"seed\": 7");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u);
  expectAt(ds[0], text, "\"duration\"");
  EXPECT_TRUE(contains(ds[0].what, "JSON syntax error")) << ds[0].format();
  EXPECT_EQ(ds[0].expected, "',' or '}'");
}

TEST(ScenarioErrors, JsonSyntaxErrorsNameTheCommonMistakes) {
  const std::string trailing = edit(kBottleneck, "\"radius\": 0.2}", "\"radius\": 0.2,}");
  auto ds = errorsOf(trailing);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, posOf(trailing, ",}").first);
  EXPECT_EQ(ds[0].column, posOf(trailing, ",}").second + 1);
  EXPECT_TRUE(contains(ds[0].hint, "trailing comma")) << ds[0].format();

  ds = errorsOf("{'format': 1}");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 1);
  EXPECT_EQ(ds[0].column, 2);
  EXPECT_TRUE(contains(ds[0].what, "double quotes")) << ds[0].format();

  ds = errorsOf("");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 1);
  EXPECT_EQ(ds[0].expected, "a JSON object");

  ds = errorsOf("{\"a\": \"unterminated\n}");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].line, 1);
  EXPECT_EQ(ds[0].column, 20);

  ds = errorsOf("{\"format\": \"throng/1\", \"format\": \"throng/1\"}");
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].column, 24);
  EXPECT_EQ(ds[0].pointer, "/format");
  EXPECT_TRUE(contains(ds[0].what, "duplicate key")) << ds[0].format();

  ds = errorsOf(std::string(200, '[') + std::string(200, ']'));
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_TRUE(contains(ds[0].what, "nesting")) << ds[0].format();
}

TEST(ScenarioErrors, UnknownKeyWithDidYouMean) {
  const std::string text = edit(kBottleneck, "\"spawn\"", "\"spwan\"");
  const auto ds = errorsOf(text);
  const auto d = at(ds, "/populations/0/spwan");
  expectAt(d, text, "\"spwan\"");
  EXPECT_EQ(d.what, "unknown key \"spwan\" in a population");
  EXPECT_TRUE(contains(d.expected, "one of: id, groups, size, spawn")) << d.format();
  EXPECT_EQ(d.hint, "did you mean \"spawn\"?");
  // ... and the now-missing spawn is reported too, at the population object.
  const auto missing = at(ds, "/populations/0");
  EXPECT_EQ(missing.what, "missing required key \"spawn\"");
  expectAt(missing, text, "{\"id\": \"crowd\"");
}

TEST(ScenarioErrors, WrongType) {
  const std::string text = edit(kBottleneck, "\"seed\": 7", "\"seed\": \"7\"");
  const auto d = at(errorsOf(text), "/seed");
  expectAt(d, text, "\"7\"");
  EXPECT_EQ(d.what, "wrong type: a string");
  EXPECT_TRUE(contains(d.expected, "an integer")) << d.format();

  const std::string groups = edit(kBottleneck, "\"groups\": 100", "\"groups\": [100]");
  const auto g = at(errorsOf(groups), "/populations/0/groups");
  expectAt(g, groups, "[100]");
  EXPECT_EQ(g.what, "wrong type: an array");
  EXPECT_EQ(g.expected, "an integer from 1 to 1e+07 groups");

  const std::string vertex = edit(kBottleneck, "[20,10]", "[20,\"10\"]");
  const auto v = at(errorsOf(vertex), "/walkable/0/2/1");
  expectAt(v, vertex, "\"10\"");
}

TEST(ScenarioErrors, MissingRequiredKeys) {
  const std::string text = edit(edit(kBottleneck, "\"format\": \"throng/1\",", ""), "\"walkable\"", "\"walkables\"");
  const auto ds = errorsOf(text);
  bool format = false, walkable = false;
  for (const auto& d : ds) {
    if (d.pointer.empty() && d.what == "missing required key \"format\"") {
      format = true;
      EXPECT_EQ(d.expected, "\"throng/1\"");
      EXPECT_EQ(d.line, 1);
      EXPECT_EQ(d.column, 1);
    }
    if (d.pointer.empty() && d.what == "missing required key \"walkable\"") walkable = true;
  }
  EXPECT_TRUE(format && walkable) << core::formatAll(ds);
  EXPECT_EQ(at(ds, "/walkables").hint, "did you mean \"walkable\"?");

  const std::string wrongFormat = edit(kBottleneck, "throng/1", "throng/2");
  const auto f = at(errorsOf(wrongFormat), "/format");
  EXPECT_EQ(f.what, "unsupported format \"throng/2\"");
}

TEST(ScenarioErrors, ValuesOutOfRangeNameUnits) {
  const std::string text = edit(kBottleneck, "\"duration\": 300,", "\"duration\": 300, \"dt\": 0.7,");
  const auto d = at(errorsOf(text), "/dt");
  expectAt(d, text, "0.7");
  EXPECT_EQ(d.what, "value 0.7 s is out of range");
  EXPECT_EQ(d.expected, "a number from 0.001 to 0.5 s");
  EXPECT_EQ(d.format(), "t.json:5:26 /dt: value 0.7 s is out of range; expected a number from 0.001 to 0.5 s");

  const auto r = at(errorsOf(edit(kBottleneck, "\"radius\": 0.2", "\"radius\": 2")), "/populations/0/radius");
  EXPECT_EQ(r.what, "value 2 m is out of range");
  EXPECT_EQ(r.expected, "a number from 0.05 to 1 m");

  const auto dur = at(errorsOf(edit(kBottleneck, "\"duration\": 300", "\"duration\": -1")), "/duration");
  EXPECT_EQ(dur.expected, "a number > 0 and <= 1e+06 s");

  const auto speed = at(errorsOf(edit(kBottleneck, "\"sd\": 0.26", "\"sd\": 0.26, \"max\": 1.0")), "/populations/0/speed/mean");
  EXPECT_TRUE(contains(speed.what, "outside [min, max]")) << speed.format();

  const auto size = at(errorsOf(edit(kBottleneck, "\"size\": 1", "\"size\": [4, 2]")), "/populations/0/size");
  EXPECT_TRUE(contains(size.what, "is empty")) << size.format();

  const auto seed = at(errorsOf(edit(kBottleneck, "\"seed\": 7", "\"seed\": -7")), "/seed");
  EXPECT_TRUE(contains(seed.what, "negative")) << seed.format();
}

TEST(ScenarioErrors, SelfIntersectingPolygon) {
  const std::string text = edit(kBottleneck, "[[1,1],[8,1],[8,9],[1,9]]", "[[1,1],[8,9],[8,1],[1,9]]");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  const auto d = at(ds, "/populations/0/spawn/polygon/2");
  expectAt(d, text, "[8,1],[1,9]");
  EXPECT_EQ(d.what, "self-intersecting polygon: edge 2→3 crosses edge 0→1");
  EXPECT_TRUE(contains(d.expected, "simple polygon")) << d.format();
}

TEST(ScenarioErrors, DegeneratePolygons) {
  const std::string two = edit(kBottleneck, "[[0,0],[20,0],[20,10],[0,10]]", "[[0,0],[20,0],[20,0],[0,0]]");
  const auto d = at(errorsOf(two), "/walkable/0");
  expectAt(d, two, "[[0,0],[20,0],[20,0]");
  EXPECT_EQ(d.what, "degenerate polygon: 2 distinct points");
  EXPECT_EQ(d.expected, "at least 3 distinct points");

  const std::string flat = edit(kBottleneck, "[[19,4],[20,4],[20,6],[19,6]]", "[[19,4],[20,4],[21,4]]");
  const auto f = at(errorsOf(flat), "/points/1/polygon");
  EXPECT_TRUE(contains(f.what, "zero area")) << f.format();

  const std::string empty = edit(kBottleneck, "[[9,0],[10,0],[10,4.5],[9,4.5]]", "[]");
  EXPECT_EQ(at(errorsOf(empty), "/obstacles/0").what, "degenerate polygon: 0 distinct points");
}

TEST(ScenarioErrors, SpawnOutsideWalkableOrInObstacleOrTooSmall) {
  const std::string outside = edit(kBottleneck, "[[1,1],[8,1],[8,9],[1,9]]", "[[-5,1],[8,1],[8,9],[-5,9]]");
  const auto o = at(errorsOf(outside), "/populations/0/spawn/polygon");
  expectAt(o, outside, "[[-5,1]");
  EXPECT_EQ(o.what, "spawn area lies partly outside the walkable area (40 of 104 m² outside)");
  EXPECT_EQ(o.expected, "a spawn inside /walkable and clear of /obstacles");

  const std::string far = edit(kBottleneck, "[[1,1],[8,1],[8,9],[1,9]]", "[[30,1],[38,1],[38,9],[30,9]]");
  EXPECT_TRUE(contains(at(errorsOf(far), "/populations/0/spawn/polygon").what, "entirely outside"));

  const std::string obstacle = edit(kBottleneck, "[[1,1],[8,1],[8,9],[1,9]]", "[[1,1],[9.5,1],[9.5,9],[1,9]]");
  const auto ob = at(errorsOf(obstacle), "/populations/0/spawn/polygon");
  EXPECT_TRUE(contains(ob.what, "overlaps obstacle /obstacles/0, /obstacles/1")) << ob.format();

  const std::string position = edit(kBottleneck, "{\"polygon\": [[1,1],[8,1],[8,9],[1,9]]}", "{\"position\": [9.5, 2]}");
  const auto p = at(errorsOf(position), "/populations/0/spawn/position");
  EXPECT_EQ(p.what, "spawn position (9.5, 2) is inside obstacle /obstacles/0");

  const std::string small = edit(kBottleneck, "[[1,1],[8,1],[8,9],[1,9]]", "[[1,1],[3,1],[3,3],[1,3]]");
  const auto s = at(errorsOf(small), "/populations/0/spawn/polygon");
  EXPECT_EQ(s.what, "spawn area of 4 m² is too small for 100 agents of radius 0.2 m");
  EXPECT_EQ(s.expected, "at least 25.1 m² (agents × π r² / packing factor 0.5)");

  // A spawn point's disc region counts too.
  const std::string point = edit(edit(edit(kBottleneck, "\"radius\": 0.5}", "\"radius\": 1.5}"), "{\"polygon\": [[1,1],[8,1],[8,9],[1,9]]}", "{\"point\": \"gap\"}"),
                                 "\"groups\": 100", "\"groups\": 1");
  // (gap's disc, 1.5 m instead of 0.5 m, now spills into the walls beside the gap)
  EXPECT_TRUE(contains(at(errorsOf(point), "/populations/0/spawn/point").what, "overlaps obstacle"));
}

TEST(ScenarioErrors, UnknownGoalWithDidYouMean) {
  const std::string text = edit(kBottleneck, "[\"gap\", \"exit\"]", "[\"gap\", \"exitt\"]");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  expectAt(ds[0], text, "\"exitt\"");
  EXPECT_EQ(ds[0].format(), "t.json:14:23 /populations/0/goals/1: unknown point \"exitt\"; expected an id from /points "
                            "(did you mean \"exit\"?)");
  const std::string spawn = edit(kBottleneck, "{\"polygon\": [[1,1],[8,1],[8,9],[1,9]]}", "{\"point\": \"gapp\"}");
  EXPECT_EQ(at(errorsOf(spawn), "/populations/0/spawn/point").hint, "did you mean \"gap\"?");
}

TEST(ScenarioErrors, DuplicatePointIds) {
  const std::string text = edit(kBottleneck, "{\"id\": \"exit\"", "{\"id\": \"gap\"");
  const auto d = at(errorsOf(text), "/points/1/id");
  expectAt(d, text, "\"gap\"", 1);
  EXPECT_EQ(d.what, "duplicate point id \"gap\"");
  EXPECT_EQ(d.hint, "first used at /points/0");
}

TEST(ScenarioErrors, PointKindAndActionKeys) {
  const auto k = at(errorsOf(edit(kBottleneck, "\"kind\": \"exit\"", "\"kind\": \"exti\"")), "/points/1/kind");
  EXPECT_EQ(k.hint, "did you mean \"exit\"?");
  const auto s = at(errorsOf(edit(kBottleneck, "\"radius\": 0.5}", "\"radius\": 0.5, \"stop\": true}")), "/points/0/stop");
  EXPECT_EQ(s.what, "\"stop\" only applies to action points");
}

TEST(ScenarioErrors, EveryProblemIsReported) {
  std::string text = edit(kBottleneck, "\"seed\": 7", "\"seed\": 7.5");
  text = edit(text, "\"exit\"]", "\"exi\"]");
  text = edit(text, "\"radius\": 0.2", "\"radius\": 0.01");
  text = edit(text, "\"name\"", "\"nmae\"");
  const auto ds = errorsOf(text);
  EXPECT_EQ(ds.size(), 4u) << core::formatAll(ds);
  for (std::size_t i = 1; i < ds.size(); ++i) EXPECT_LE(ds[i - 1].line, ds[i].line);  // file order
}

TEST(ScenarioErrors, UnreachableGoal) {
  // A wall closes the gap: the exit cannot be reached from the spawn.
  const std::string text = edit(kBottleneck, "[[9,5.5],[10,5.5],[10,10],[9,10]]", "[[9,4],[10,4],[10,10],[9,10]]");
  const auto ds = errorsOf(text, true);
  const auto d = at(ds, "/populations/0/goals/1");
  expectAt(d, text, "\"exit\"]");
  EXPECT_EQ(d.what, "point \"exit\" cannot be reached from the spawn area of population \"crowd\"");
  // The real limit, not 2 × radius: the default model's navmesh keeps centres 0.2 × 0.65 m (shoulders
  // turned) from walls, rounded up to whole cells, so openings narrower than 0.325 m close.
  EXPECT_TRUE(contains(d.expected, "at least 0.325 m wide")) << d.format();
  EXPECT_TRUE(contains(d.expected, "keeps body centres 0.162 m from walls: body radius 0.2 m × the model's passage ratio"))
      << d.format();
}

TEST(ScenarioErrors, PointOutsideTheWalkableArea) {
  // A typo in a point's coordinates puts it in the void: named even when no population uses it.
  const std::string text = edit(kBottleneck, R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]})",
                                R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]},
    {"id": "island", "kind": "interest", "position": [50, 50], "radius": 1})");
  const auto ds = errorsOf(text, true);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  const auto d = at(ds, "/points/2");
  EXPECT_TRUE(contains(d.what, "\"island\" at (50, 50) lies outside the walkable area")) << d.format();
  EXPECT_EQ(d.expected, "a region that overlaps /walkable");
  EXPECT_GT(d.line, 0);
}

TEST(ScenarioErrors, ReachableScenarioBuildsNavmesh) {
  auto r = load(kBottleneck, true);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_NE(r->navmesh, nullptr);
}

TEST(ScenarioErrors, DemographicSpeeds) {
  const std::string ok = edit(kBottleneck, R"("speed": {"mean": 1.34, "sd": 0.26})",
                              R"("speed": {"demographics": "weidmann-age", "age": [20, 60], "impaired": 0.1, "impairedRadius": 0.4})");
  auto r = load(ok);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::PopulationDesc& p = r.value().desc.populations[0];
  EXPECT_EQ(p.demographics.table, sim::SpeedTable::WeidmannAge);
  EXPECT_FLOAT_EQ(p.demographics.ageMin, 20.0f);
  EXPECT_FLOAT_EQ(p.demographics.ageMax, 60.0f);
  EXPECT_FLOAT_EQ(p.demographics.impaired, 0.1f);
  EXPECT_FLOAT_EQ(p.demographics.impairedRadius, 0.4f);
  EXPECT_FLOAT_EQ(r.value().desc.maxRadius(), 0.4f);  // the navmesh is eroded for the largest body
  // Without the key: no table.
  EXPECT_EQ(load(kBottleneck).value().desc.populations[0].demographics.table, sim::SpeedTable::None);

  const std::string typo = edit(kBottleneck, R"("sd": 0.26})", R"("sd": 0.26, "demographics": "weidman-age"})");
  const auto ds = errorsOf(typo);
  const auto table = at(ds, "/populations/0/speed/demographics");
  EXPECT_EQ(table.what, "unknown speed table \"weidman-age\"");
  EXPECT_EQ(table.hint, "did you mean \"weidmann-age\"?");
  expectAt(table, typo, "\"weidman-age\"");
  EXPECT_EQ(table.format(), "t.json:14:84 /populations/0/speed/demographics: unknown speed table \"weidman-age\"; "
                            "expected \"weidmann-age\" (did you mean \"weidmann-age\"?)");
  EXPECT_TRUE(contains(at(ds, "/populations/0/speed/mean").what, "next to \"demographics\"")) << core::formatAll(ds);
  EXPECT_TRUE(contains(at(ds, "/populations/0/speed/sd").what, "next to \"demographics\""));

  const auto ages = errorsOf(edit(kBottleneck, R"("speed": {"mean": 1.34, "sd": 0.26})",
                                  R"("speed": {"demographics": "weidmann-age", "age": [2, 90], "impaired": 1.5})"));
  EXPECT_EQ(at(ages, "/populations/0/speed/age/0").what, "value 2 years is out of range");
  EXPECT_EQ(at(ages, "/populations/0/speed/age/0").expected, "a number from 5 to 80 years");
  EXPECT_EQ(at(ages, "/populations/0/speed/impaired").what, "value 1.5 is out of range");

  const auto orphan = errorsOf(edit(kBottleneck, R"("sd": 0.26})", R"("sd": 0.26, "impaired": 0.2})"));
  EXPECT_EQ(at(orphan, "/populations/0/speed/impaired").what, "\"impaired\" needs a demographic table");
}

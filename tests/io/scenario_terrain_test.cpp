// Tests for multi-level scenarios (libs/io scenario_terrain_parser, scenario_parser,
// scenario_crowd_parser, scenario_validator, crowd_parser): "terrain" vertices and triangles,
// positions with heights ([x, y, z], a polygon spawn's "height", a spawn at a point), the refusal
// of heights in flat worlds and of 2D-only features on multi-level ones, and the validator's
// checks on the 3D navmesh (points and spawns at their floor's height, goals reachable across
// floors), and each population's speed factors on stairs ("stairs"). Diagnostics are checked word
// for word with their line:column.
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::io::test {
namespace {

/// A hall (12 m x 8 m at height 0), a 27° ramp up to an upper floor (12 m x 6 m at 3 m) behind it.
const std::string kLevels = R"({
  "format": "throng/1",
  "terrain": {
    "vertices": [[0,0,0],[12,0,0],[12,8,0],[0,8,0],[12,14,3],[0,14,3],[12,20,3],[0,20,3]],
    "walkable": [[0,1,2],[0,2,3],[3,2,4],[3,4,5],[5,4,6],[5,6,7]]
  },
  "points": [
    {"id": "hall", "kind": "interest", "position": [6, 4]},
    {"id": "top", "kind": "action", "position": [6, 17, 3], "duration": 2},
    {"id": "room", "kind": "interest", "polygon": [[2,16],[4,16],[4,18],[2,18]], "height": 3}
  ],
  "populations": [
    {"id": "up", "groups": 2, "spawn": {"position": [2, 2, 0]}, "goals": ["top", "hall"]},
    {"id": "down", "spawn": {"polygon": [[8,16],[10,16],[10,18],[8,18]], "height": 3}, "goals": ["hall"]},
    {"id": "at", "spawn": {"point": "top"}, "goals": ["room"],
     "guide": {"script": [{"time": 0, "position": [6, 17, 3]}, {"time": 10, "position": [6, 4]}]}}
  ]
}
)";

std::string change(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(ScenarioTerrain, ParsesTerrainAndHeights) {
  auto r = load(kLevels);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r.value().desc;
  EXPECT_TRUE(d.walkable.empty());
  EXPECT_TRUE(d.obstacles.empty());
  ASSERT_EQ(d.terrain.vertices.size(), 24u);
  EXPECT_FLOAT_EQ(d.terrain.vertices[3 * 4 + 2], 3.0f);
  ASSERT_EQ(d.terrain.walkable.size(), 18u);
  EXPECT_EQ(d.terrain.walkable[17], 7u);
  EXPECT_TRUE(d.terrain.obstacles.empty());
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_FLOAT_EQ(d.points[0].height, 0.0f);
  EXPECT_FLOAT_EQ(d.points[1].height, 3.0f);
  EXPECT_FLOAT_EQ(d.points[1].position.x, 6.0f);
  EXPECT_FLOAT_EQ(d.points[1].position.y, 17.0f);
  EXPECT_FLOAT_EQ(d.points[2].height, 3.0f);  // a polygon point's "height"
  ASSERT_EQ(d.populations.size(), 3u);
  EXPECT_EQ(d.populations[0].spawn.kind, sim::SpawnKind::Position);
  EXPECT_FLOAT_EQ(d.populations[0].spawn.height, 0.0f);
  EXPECT_EQ(d.populations[1].spawn.kind, sim::SpawnKind::Polygon);
  EXPECT_FLOAT_EQ(d.populations[1].spawn.height, 3.0f);
  EXPECT_EQ(d.populations[2].spawn.kind, sim::SpawnKind::Point);
  EXPECT_FLOAT_EQ(d.populations[2].spawn.height, 3.0f);  // the point's own height
  ASSERT_EQ(d.populations[2].guide.script.size(), 2u);
  EXPECT_FLOAT_EQ(d.populations[2].guide.script[0].height, 3.0f);
  EXPECT_FLOAT_EQ(d.populations[2].guide.script[1].height, 0.0f);  // [x, y]: height 0
}

TEST(ScenarioTerrain, ObstacleTrianglesAreRead) {
  const std::string text = change(kLevels, R"("walkable": [[0,1,2],)", R"("obstacles": [[0,1,3]], "walkable": [[0,1,2],)");
  auto r = load(text);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  ASSERT_EQ(r.value().desc.terrain.obstacles.size(), 3u);
  EXPECT_EQ(r.value().desc.terrain.obstacles[2], 3u);
}

TEST(ScenarioTerrain, StairFactorsPerPopulation) {
  const std::string text = change(kLevels, R"("goals": ["hall"]},)", R"("goals": ["hall"], "stairs": {"up": 0.4, "down": 0.9, "climb": {"up": 1, "down": 0}}},)");
  auto r = load(text);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::PopulationDesc& down = r.value().desc.populations[1];
  EXPECT_FLOAT_EQ(down.stairUp, 0.4f);
  EXPECT_FLOAT_EQ(down.stairDown, 0.9f);
  EXPECT_FLOAT_EQ(down.stairClimbUp, 1.0f);
  EXPECT_FLOAT_EQ(down.stairClimbDown, 0.0f);
  // Without the key: the defaults (Weidmann 1993 along a 30° stair; Zacharias & Ling 2014's shares).
  const sim::PopulationDesc& up = r.value().desc.populations[0];
  EXPECT_FLOAT_EQ(up.stairUp, 0.53f);
  EXPECT_FLOAT_EQ(up.stairDown, 0.60f);
  EXPECT_FLOAT_EQ(up.stairClimbUp, 0.203f);
  EXPECT_FLOAT_EQ(up.stairClimbDown, 0.311f);
}

TEST(ScenarioTerrain, BadStairFactorsAreLocated) {
  std::string text = change(kLevels, R"("goals": ["top", "hall"]},)", R"("goals": ["top", "hall"], "stairs": {"up": 0, "down": 1.5, "sideways": 1, "climb": {"up": -0.1, "along": 1}}},)");
  text = change(text, R"("goals": ["hall"]},)", R"("goals": ["hall"], "stairs": 0.5},)");
  const auto ds = errorsOf(text);
  const auto up = at(ds, "/populations/0/stairs/up");
  EXPECT_EQ(up.what, "value 0 is out of range");
  EXPECT_EQ(up.expected, "a number > 0 and <= 1");
  expectAt(up, text, "0, \"down\"");
  EXPECT_EQ(at(ds, "/populations/0/stairs/down").what, "value 1.5 is out of range");
  EXPECT_TRUE(contains(at(ds, "/populations/0/stairs/sideways").what, "unknown key \"sideways\""));
  const auto shape = at(ds, "/populations/1/stairs");
  EXPECT_EQ(shape.expected, "{\"up\", \"down\", \"climb\"}: factors of the desired speed on stairs, each > 0 and <= 1");
  const auto climb = at(ds, "/populations/0/stairs/climb/up");
  EXPECT_EQ(climb.what, "value -0.1 is out of range");
  EXPECT_EQ(climb.expected, "a number from 0 to 1");
  expectAt(climb, text, "-0.1, \"along\"");
  EXPECT_TRUE(contains(at(ds, "/populations/0/stairs/climb/along").what, "unknown key \"along\""));
  EXPECT_EQ(ds.size(), 6u) << core::formatAll(ds);
}

TEST(ScenarioTerrain, IndexOutOfRange) {
  const std::string text = change(kLevels, "[5,6,7]]", "[5,6,8]]");
  const auto d = at(errorsOf(text), "/terrain/walkable/5/2");
  EXPECT_EQ(d.what, "index 8 is out of range: /terrain/vertices has 8 vertices");
  EXPECT_EQ(d.expected, "a triangle [i, j, k]: three different vertex indices from 0 to 7 (into /terrain/vertices)");
  expectAt(d, text, "8]]");
}

TEST(ScenarioTerrain, BadVerticesAndTriangles) {
  std::string text = change(kLevels, "[0,20,3]]", "[0,20]]");
  text = change(text, "[12,0,0]", "[12,0,1e6]");
  text = change(text, "[0,2,3],", "[0,2,2.5],");
  text = change(text, "[3,2,4],", "[3,3,4],");
  text = change(text, "[3,4,5],", "[3,4],");
  const auto ds = errorsOf(text);
  const auto v = at(ds, "/terrain/vertices/7");
  EXPECT_EQ(v.what, "vertex has 2 coordinates");
  EXPECT_EQ(v.expected, "a vertex [x, y, z] of three finite numbers in metres, each within ±100000");
  expectAt(v, text, "[0,20]]");
  EXPECT_EQ(at(ds, "/terrain/vertices/1/2").what, "value 1e+06 m is out of range");
  EXPECT_EQ(at(ds, "/terrain/walkable/1/2").what, "index 2.5 is not a whole number");
  const auto degenerate = at(ds, "/terrain/walkable/2");
  EXPECT_EQ(degenerate.what, "degenerate triangle: vertex 3 used twice");
  expectAt(degenerate, text, "[3,3,4]");
  EXPECT_EQ(at(ds, "/terrain/walkable/3").what, "triangle has 2 indices");
  EXPECT_EQ(ds.size(), 5u) << core::formatAll(ds);
}

TEST(ScenarioTerrain, NeedsVerticesAndAWalkableTriangle) {
  const std::string noWalk = change(kLevels, R"("walkable": [[0,1,2],[0,2,3],[3,2,4],[3,4,5],[5,4,6],[5,6,7]])",
                                    R"("walkable": [])");
  const auto d = at(errorsOf(noWalk), "/terrain/walkable");
  EXPECT_EQ(d.what, "no walkable triangle");
  EXPECT_EQ(d.expected, "an array of at least one triangle [i, j, k] (indices into /terrain/vertices)");
  const std::string noVerts = change(kLevels, R"("vertices": [[0,0,0],[12,0,0],[12,8,0],[0,8,0],[12,14,3],[0,14,3],[12,20,3],[0,20,3]],)",
                                     "");
  const auto ds = errorsOf(noVerts);
  EXPECT_EQ(at(ds, "/terrain").what, "missing required key \"vertices\"");
  EXPECT_EQ(at(ds, "/terrain/walkable/0/0").what, "index 0 is out of range: /terrain/vertices has 0 vertices");
}

TEST(ScenarioTerrain, TooManyBadTrianglesAreSummarised) {
  std::string many;
  for (int i = 0; i < 30; ++i) many += "[0,1,99],";
  const std::string text = change(kLevels, R"("walkable": [)", R"("walkable": [)" + many);
  const auto ds = errorsOf(text);
  EXPECT_EQ(ds.size(), 21u) << core::formatAll(ds);
  EXPECT_EQ(at(ds, "/terrain/walkable").what, "and 10 more bad triangles in /terrain/walkable");
}

TEST(ScenarioTerrain, PolygonGeometryNextToTerrainIsRefused) {
  const std::string text = change(kLevels, R"("terrain": {)",
                                  R"("walkable": [[[0,0],[1,0],[1,1]]], "obstacles": [[[0,0],[1,0],[1,1]]], "terrain": {)");
  const auto ds = errorsOf(text);
  const auto w = at(ds, "/walkable");
  EXPECT_EQ(w.what, "a multi-level world takes its walkable surface from /terrain/walkable");
  EXPECT_EQ(w.expected, "no \"walkable\" (or an empty array) next to \"terrain\"");
  expectAt(w, text, "\"walkable\"");
  const auto o = at(ds, "/obstacles");
  EXPECT_EQ(o.what, "a multi-level world takes its obstacles from /terrain/obstacles");
  EXPECT_EQ(o.expected, "no \"obstacles\" (or an empty array) next to \"terrain\"");
  // Empty lists are fine.
  const std::string empty = change(kLevels, R"("terrain": {)", R"("walkable": [], "obstacles": [], "terrain": {)");
  EXPECT_TRUE(load(empty).ok());
}

TEST(ScenarioTerrain, HeightsNeedAMultiLevelWorld) {
  std::string text = edit(kBottleneck, R"("position": [9.5, 5])", R"("position": [9.5, 5, 2.5])");
  const auto d = at(errorsOf(text), "/points/0/position/2");
  EXPECT_EQ(d.what, "height 2.5 m in a flat world: heights need a multi-level world (/terrain)");
  EXPECT_EQ(d.expected, "no height (or 0) in a world of /walkable polygons");
  expectAt(d, text, "2.5]");
  // A polygon spawn's "height" likewise; a height of 0 is accepted.
  text = edit(kBottleneck, R"({"polygon": [[1,1],[8,1],[8,9],[1,9]]})", R"({"polygon": [[1,1],[8,1],[8,9],[1,9]], "height": 1})");
  EXPECT_EQ(at(errorsOf(text), "/populations/0/spawn/height").what,
            "height 1 m in a flat world: heights need a multi-level world (/terrain)");
  text = edit(kBottleneck, R"("position": [9.5, 5])", R"("position": [9.5, 5, 0])");
  EXPECT_TRUE(load(text).ok());
}

TEST(ScenarioTerrain, PositionShapesAndHeightKeys) {
  auto ds = errorsOf(change(kLevels, "[2, 2, 0]", "[2, 2, 0, 1]"));
  const auto d = at(ds, "/populations/0/spawn/position");
  EXPECT_EQ(d.what, "point has 4 coordinates");
  EXPECT_EQ(d.expected,
            "a position [x, y] or [x, y, z] of numbers in metres (z: the floor's height, multi-level worlds only), each "
            "within ±100000");
  ds = errorsOf(change(kLevels, R"({"position": [2, 2, 0]})", R"({"position": [2, 2], "height": 0})"));
  EXPECT_EQ(at(ds, "/populations/0/spawn/height").what, "\"height\" only applies to a polygon spawn");
  EXPECT_EQ(at(ds, "/populations/0/spawn/height").expected, "the height as the position's z: [x, y, z]");
  ds = errorsOf(change(kLevels, R"({"point": "top"})", R"({"point": "top", "height": 3})"));
  EXPECT_EQ(at(ds, "/populations/2/spawn/height").expected, "no \"height\" (a spawn at a point takes the point's height)");
  ds = errorsOf(change(kLevels, R"("position": [6, 4]})", R"("position": [6, 4], "height": 1})"));
  EXPECT_EQ(at(ds, "/points/0/height").what, "\"height\" only applies to a polygon region");
}

TEST(ScenarioTerrain, TwoDimensionalFeaturesAreRefused) {
  std::string text = change(kLevels, R"("goals": ["top", "hall"]})", R"("goals": "auto", "paths": "bezier"})");
  auto ds = errorsOf(text);
  const auto goals = at(ds, "/populations/0/goals");
  EXPECT_EQ(goals.what, "\"goals\": \"auto\" is not supported on multi-level worlds yet");
  EXPECT_EQ(goals.expected, "an array of point ids from /points (the goals listed)");
  const auto paths = at(ds, "/populations/0/paths");
  EXPECT_EQ(paths.what, "\"paths\": \"bezier\" is not supported on multi-level worlds yet");
  EXPECT_EQ(paths.expected, "\"navmesh\" (or no \"paths\")");
  expectAt(paths, text, "\"bezier\"");
  text = change(kLevels, R"("format": "throng/1",)", R"("format": "throng/1", "social": {},)");
  const auto social = at(errorsOf(text), "/social");
  EXPECT_EQ(social.what, "the \"social\" section (Common Ground) is not supported on multi-level worlds yet");
  EXPECT_EQ(social.expected, "no \"social\" section next to \"terrain\"");
  expectAt(social, text, "\"social\"");
}

/// Whether the loaded navmesh's ground halfway up the 27° ramp of kLevels is a stair.
bool rampIsStair(const LoadedScenario& loaded) {
  nav::NavQuery query(loaded.navmesh);
  const auto hit = query.snap({6, 11}, 1.5f, 1.0f);
  EXPECT_TRUE(hit);
  return hit && loaded.navmesh->surface(hit->ref).stair;
}

TEST(ScenarioTerrain, StairSlopeSetsWhatCountsAsAStair) {
  // Default 15°: the 27° ramp is walked as a stair. "stairSlope": 30: as level ground.
  auto plain = load(kLevels, true);
  ASSERT_TRUE(plain.ok()) << core::formatAll(plain.errors());
  EXPECT_FLOAT_EQ(plain.value().desc.stairSlopeDeg, 15.0f);
  EXPECT_TRUE(rampIsStair(plain.value()));
  auto gentle = load(change(kLevels, R"("terrain": {)", R"("terrain": {"stairSlope": 30,)"), true);
  ASSERT_TRUE(gentle.ok()) << core::formatAll(gentle.errors());
  EXPECT_FLOAT_EQ(gentle.value().desc.stairSlopeDeg, 30.0f);
  EXPECT_FLOAT_EQ(gentle.value().navmesh->config().stairSlopeDeg, 30.0f);
  EXPECT_FALSE(rampIsStair(gentle.value()));
}

TEST(ScenarioTerrain, BadStairSlopeIsLocated) {
  for (const char* bad : {"0", "-5", "90", "\"steep\""}) {
    const std::string text = change(kLevels, R"("terrain": {)", std::string(R"("terrain": {"stairSlope": )") + bad + ",");
    const auto ds = errorsOf(text);
    ASSERT_EQ(ds.size(), 1u) << bad << ": " << core::formatAll(ds);
    const auto d = at(ds, "/terrain/stairSlope");
    EXPECT_EQ(d.expected, "a number > 0 and <= 89 degrees") << bad;
    expectAt(d, text, std::string(bad) + ",\n    \"vertices\"");
  }
  EXPECT_EQ(at(errorsOf(change(kLevels, R"("terrain": {)", R"("terrain": {"stairSlope": 90,)")), "/terrain/stairSlope").what,
            "value 90 degrees is out of range");
}

TEST(ScenarioTerrain, ValidatesOnTheNavmeshAcrossFloors) {
  auto r = load(kLevels, true);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  ASSERT_NE(r.value().navmesh, nullptr);
  EXPECT_TRUE(r.value().navmesh->layered());
}

TEST(ScenarioTerrain, UnconnectedFloorsMakeGoalsUnreachable) {
  const std::string text = change(kLevels, "[3,2,4],[3,4,5],", "");
  const auto ds = errorsOf(text, true);
  const auto d = at(ds, "/populations/0/goals/0");
  EXPECT_EQ(d.what, "point \"top\" cannot be reached from the spawn area of population \"up\"");
  EXPECT_NE(d.expected.find("steps at most 0.35 m high"), std::string::npos) << d.expected;
  at(ds, "/populations/1/goals/0");  // down to the hall: no way either
  EXPECT_EQ(ds.size(), 2u) << core::formatAll(ds);  // the hall's "up" goal and "at" → room stay fine
}

TEST(ScenarioTerrain, HeightsPickTheFloor) {
  // Nothing walkable at height 0 behind the ramp: the upper floor is 3 m up, beyond the search band.
  std::string text = change(kLevels, "[6, 17, 3]", "[6, 17, 0]");
  auto ds = errorsOf(text, true);
  EXPECT_EQ(at(ds, "/points/1").what,
            "point \"top\" at (6, 17, 0) lies off the walkable surface (nothing walkable within 1.5 m at heights within ±1.5 m)");
  text = change(kLevels, R"("height": 3}, "goals")", R"("height": 7}, "goals")");
  ds = errorsOf(text, true);
  const auto d = at(ds, "/populations/1/spawn/polygon");
  EXPECT_EQ(d.what,
            "spawn area at height 7 m is off the walkable surface (nothing walkable within 1.41 m of its centre (9, 17, 7) at "
            "heights within ±1.5 m)");
  EXPECT_EQ(d.hint, "give the floor's height as \"height\" next to \"polygon\"");
  text = change(kLevels, "[2, 2, 0]", "[2, 2, 3]");
  EXPECT_EQ(at(errorsOf(text, true), "/populations/0/spawn/position").what,
            "spawn position (2, 2, 3) is off the walkable surface (nothing walkable within 1 m at heights within ±1.5 m)");
  text = change(kLevels, R"("position": [6, 4]}]})", R"("position": [6, 4, 3]}]})");
  EXPECT_EQ(at(errorsOf(text, true), "/populations/2/guide/script/1/position").what,
            "guide waypoint (6, 4, 3) is off the walkable surface (nothing walkable within 1 m at heights within ±1.5 m)");
}

TEST(ScenarioTerrain, CrowdFilesCarryHeights) {
  auto world = load(kLevels, true);
  ASSERT_TRUE(world.ok()) << core::formatAll(world.errors());
  CrowdOptions options;
  options.navmesh = world.value().navmesh;
  const std::string crowd = R"({"format": "throng-crowd/1", "id": "late",
    "points": [{"id": "landing", "kind": "interest", "position": [6, 15, 3]}],
    "populations": [{"id": "late_up", "spawn": {"position": [10, 2, 0]}, "goals": ["landing", "room"]},
                    {"id": "late_top", "spawn": {"point": "landing"}, "goals": ["hall"]}]})";
  auto c = parseCrowd(crowd, "c.json", world.value().desc, options);
  ASSERT_TRUE(c.ok()) << core::formatAll(c.errors());
  ASSERT_EQ(c.value().points.size(), 1u);
  EXPECT_FLOAT_EQ(c.value().points[0].height, 3.0f);
  EXPECT_FLOAT_EQ(c.value().populations[1].spawn.height, 3.0f);
  // The same rules as a scenario: 2D-only features are refused, heights are checked on the mesh.
  const std::string bad = R"({"format": "throng-crowd/1", "id": "late",
    "populations": [{"id": "late_up", "spawn": {"position": [10, 2, 3]}, "goals": ["hall"], "paths": "bezier"}]})";
  auto e = parseCrowd(bad, "c.json", world.value().desc, options);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(at(e.errors(), "/populations/0/paths").what, "\"paths\": \"bezier\" is not supported on multi-level worlds yet");
  // A flat world's crowd file gets the flat-world refusal.
  auto flat = load(kBottleneck);
  ASSERT_TRUE(flat.ok());
  const std::string flatCrowd = R"({"format": "throng-crowd/1", "id": "c",
    "populations": [{"id": "p", "spawn": {"position": [2, 2, 1]}, "goals": ["exit"]}]})";
  auto f = parseCrowd(flatCrowd, "c.json", flat.value().desc);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(at(f.errors(), "/populations/0/spawn/position/2").what,
            "height 1 m in a flat world: heights need a multi-level world (/terrain)");
}

}  // namespace
}  // namespace throng::io::test

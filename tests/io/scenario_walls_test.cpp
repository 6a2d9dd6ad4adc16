// The scenario keys "walls" and "measurements" (scenario_walls_parser.cpp): walls become obstacle
// rectangles that cover their joints and behave exactly like the same polygons listed in
// "obstacles" (same trajectories, reachability, spawn checks naming the wall); measurements are
// parsed and leave the simulation unchanged; bad values get located diagnostics.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "scenario_parser.hpp"
#include "scenario_test_util.hpp"
#include "throng/core/polygon_check.hpp"
#include "throng/sim/world.hpp"

namespace throng::io::test {
namespace {

/// The bottleneck's two obstacles as walls: vertical lines at x = 9.5, 1 m thick.
const std::string kWalls =
    R"("walls": [ {"id": "south", "line": [[9.5,0.5],[9.5,4]], "thickness": 1}, {"line": [[9.5,6],[9.5,9.5]], "thickness": 1} ],)";

std::string withWalls(const std::string& walls = kWalls) {
  return edit(kBottleneck, R"("obstacles": [ [[9,0],[10,0],[10,4.5],[9,4.5]], [[9,5.5],[10,5.5],[10,10],[9,10]] ],)", walls);
}

/// Steps the world `ticks` times; the hash of every tick's state, chained.
std::uint64_t runHash(const sim::ScenarioDesc& desc, int ticks) {
  auto world = sim::World::create(desc);
  EXPECT_TRUE(world.ok());
  if (!world.ok()) return 0;
  core::TaskSystem tasks(1);
  std::uint64_t h = 14695981039346656037ull;
  for (int t = 0; t < ticks; ++t) {
    world.value()->step(tasks);
    h = (h ^ world.value()->stateHash()) * 1099511628211ull;
  }
  return h;
}

bool insideAny(const std::vector<core::Polygon>& polys, core::Vec2 p) {
  for (const auto& poly : polys) {
    if (core::pointInPolygon(poly, p)) return true;
  }
  return false;
}

TEST(ScenarioWalls, SegmentsBecomeRectanglesLengthenedByHalfTheThickness) {
  const auto footprints = wallFootprints({"w", {{0, 0}, {4, 0}, {4, 0}, {4, 3}}, 0.2f});
  ASSERT_EQ(footprints.size(), 2u);  // the repeated point adds no segment
  EXPECT_NEAR(core::signedArea(footprints[0]), 4.2 * 0.2, 1e-5);  // counter-clockwise, (L + t) × t
  EXPECT_NEAR(core::signedArea(footprints[1]), 3.2 * 0.2, 1e-5);
  const core::Vec2 expected[] = {{-0.1f, -0.1f}, {4.1f, -0.1f}, {4.1f, 0.1f}, {-0.1f, 0.1f}};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(footprints[0][std::size_t(i)].x, expected[i].x, 1e-6);
    EXPECT_NEAR(footprints[0][std::size_t(i)].y, expected[i].y, 1e-6);
  }
}

TEST(ScenarioWalls, JointsAreCoveredAtAnyAngle) {
  for (const double deg : {10.0, 45.0, 90.0, 135.0, 170.0}) {
    const double a = deg * 3.14159265358979 / 180.0;
    const core::Vec2 joint{2, 2};
    const sim::WallDesc wall{"", {{0, 2}, joint, {float(2 + 3 * std::cos(a)), float(2 + 3 * std::sin(a))}}, 0.4f};
    const auto footprints = wallFootprints(wall);
    for (int k = 0; k < 64; ++k) {  // the disc of radius t/2 around the joint, just inside its rim
      const double b = 2.0 * 3.14159265358979 * k / 64;
      const core::Vec2 p{float(joint.x + 0.199 * std::cos(b)), float(joint.y + 0.199 * std::sin(b))};
      EXPECT_TRUE(insideAny(footprints, p)) << deg << "° at " << p.x << ", " << p.y;
    }
  }
}

TEST(ScenarioWalls, AreAppendedToTheObstaclesAfterTheListedOnes) {
  auto r = load(withWalls(R"("obstacles": [ [[12,0],[13,0],[13,1],[12,1]] ],)" + kWalls));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r->desc;
  ASSERT_EQ(d.walls.size(), 2u);
  EXPECT_EQ(d.walls[0].id, "south");
  EXPECT_EQ(d.walls[1].id, "");
  EXPECT_FLOAT_EQ(d.walls[0].thickness, 1.0f);
  ASSERT_EQ(d.obstacles.size(), 3u);
  EXPECT_EQ(d.obstacles[1], wallFootprints(d.walls[0])[0]);
  EXPECT_EQ(d.obstacles[2], wallFootprints(d.walls[1])[0]);
}

TEST(ScenarioWalls, DefaultThicknessIsTwentyCentimetres) {
  auto r = load(withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,4.5]]} ],)"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_FLOAT_EQ(r->desc.walls[0].thickness, 0.2f);
}

TEST(ScenarioWalls, RunExactlyAsTheSamePolygonsListedAsObstacles) {
  auto walls = load(withWalls(), true);
  ASSERT_TRUE(walls.ok()) << core::formatAll(walls.errors());
  std::string listed = "\"obstacles\": [";
  for (const auto& poly : walls->desc.obstacles) {
    listed += std::string(listed.back() == '[' ? "" : ",") + "[";
    for (std::size_t i = 0; i < poly.size(); ++i) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s[%.9g,%.9g]", i ? "," : "", double(poly[i].x), double(poly[i].y));
      listed += buf;
    }
    listed += "]";
  }
  auto obstacles = load(withWalls(listed + "],"), true);
  ASSERT_TRUE(obstacles.ok()) << core::formatAll(obstacles.errors());
  EXPECT_EQ(obstacles->desc.obstacles, walls->desc.obstacles);
  EXPECT_EQ(runHash(walls->desc, 200), runHash(obstacles->desc, 200));
}

TEST(ScenarioWalls, ReachabilitySeesThem) {
  const std::string closed = withWalls(R"("walls": [ {"id": "closed", "line": [[9.5,0],[9.5,10]], "thickness": 0.5} ],)");
  const auto errors = errorsOf(closed, true);
  bool unreachable = false;
  for (const auto& d : errors) unreachable = unreachable || contains(d.what, "cannot be reached") || contains(d.what, "unreachable");
  EXPECT_TRUE(unreachable) << core::formatAll(errors);
  EXPECT_TRUE(load(withWalls(), true).ok());
}

TEST(ScenarioWalls, ASpawnOnAWallNamesTheWall) {
  const std::string text = edit(withWalls(), R"("spawn": {"polygon": [[1,1],[8,1],[8,9],[1,9]]})",
                                R"("spawn": {"polygon": [[9,1],[10,1],[10,3],[9,3]]})");
  const auto errors = errorsOf(text);
  const auto d = at(errors, "/populations/0/spawn/polygon");
  EXPECT_TRUE(contains(d.what, "/walls/0")) << d.format();
  EXPECT_FALSE(contains(d.what, "/obstacles")) << d.format();
}

TEST(ScenarioWalls, BadValuesAreLocated) {
  const std::string thin = withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,4.5]], "thickness": 0.001} ],)");
  const auto d1 = at(errorsOf(thin), "/walls/0/thickness");
  expectAt(d1, thin, "0.001");
  EXPECT_TRUE(contains(d1.expected, "0.01 to 5 m")) << d1.format();
  const std::string thick = withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,4.5]], "thickness": 6} ],)");
  EXPECT_TRUE(contains(at(errorsOf(thick), "/walls/0/thickness").what, "out of range"));

  const std::string point = withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,0]]} ],)");
  const auto d2 = at(errorsOf(point), "/walls/0/line");
  EXPECT_TRUE(contains(d2.what, "1 distinct point")) << d2.format();
  EXPECT_TRUE(contains(d2.expected, "at least 2 distinct points")) << d2.format();

  const std::string coordinate = withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,"x"]]} ],)");
  expectAt(at(errorsOf(coordinate), "/walls/0/line/1/1"), coordinate, "\"x\"");

  const std::string typo = withWalls(R"("walls": [ {"line": [[9.5,0],[9.5,4]], "thicknes": 1} ],)");
  const auto d3 = at(errorsOf(typo), "/walls/0/thicknes");
  EXPECT_TRUE(contains(d3.hint, "thickness")) << d3.format();

  const std::string missing = withWalls(R"("walls": [ {"id": "w"} ],)");
  EXPECT_TRUE(contains(at(errorsOf(missing), "/walls/0").what, "missing required key \"line\""));

  const std::string notArray = withWalls(R"("walls": {"line": []},)");
  EXPECT_TRUE(contains(at(errorsOf(notArray), "/walls").what, "wrong type"));

  const std::string twice = withWalls(R"("walls": [ {"id": "w", "line": [[9.5,0],[9.5,4]]}, {"id": "w", "line": [[9.5,6],[9.5,10]]} ],)");
  const auto d4 = at(errorsOf(twice), "/walls/1/id");
  EXPECT_TRUE(contains(d4.what, "duplicate wall id")) << d4.format();
  EXPECT_TRUE(contains(d4.hint, "/walls/0")) << d4.format();
}

TEST(ScenarioWalls, RefusedOnMultiLevelWorlds) {
  const std::string text = R"({"format": "throng/1",
 "terrain": {"vertices": [[0,0,0],[10,0,0],[10,0,10],[0,0,10]], "walkable": [0,1,2, 0,2,3]},
 "walls": [ {"line": [[1,1],[2,2]]} ],
 "populations": []})";
  const auto d = at(errorsOf(text), "/walls");
  EXPECT_TRUE(contains(d.what, "multi-level")) << d.format();
}

TEST(ScenarioMeasurements, LinesAndAreasAreParsed) {
  const std::string text = edit(kBottleneck, R"("points": [)", R"("measurements": [
    {"id": "m1", "line": [[10,3],[10,7]]},
    {"id": "a1", "polygon": [[7,3],[9,3],[9,7],[7,7]]}
  ],
  "points": [)");
  auto r = load(text);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  ASSERT_EQ(r->desc.measurements.size(), 2u);
  EXPECT_EQ(r->desc.measurements[0].id, "m1");
  ASSERT_EQ(r->desc.measurements[0].line.size(), 2u);
  EXPECT_EQ(r->desc.measurements[0].line[1], core::Vec2(10, 7));
  EXPECT_TRUE(r->desc.measurements[0].polygon.empty());
  EXPECT_EQ(r->desc.measurements[1].polygon.size(), 4u);
  EXPECT_TRUE(r->desc.measurements[1].line.empty());
  // Analysis only: the same trajectories as without them.
  auto plain = load(kBottleneck);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(runHash(r->desc, 100), runHash(plain->desc, 100));
}

TEST(ScenarioMeasurements, BadValuesAreLocated) {
  const auto with = [](const std::string& list) { return edit(kBottleneck, R"("points": [)", "\"measurements\": " + list + ",\n  \"points\": ["); };
  const std::string three = with(R"([{"id": "m", "line": [[0,0],[1,1],[2,2]]}])");
  const auto d1 = at(errorsOf(three), "/measurements/0/line");
  EXPECT_TRUE(contains(d1.what, "line of 3 points")) << d1.format();
  EXPECT_TRUE(contains(d1.expected, "exactly 2")) << d1.format();

  const std::string zero = with(R"([{"id": "m", "line": [[1,1],[1,1]]}])");
  EXPECT_TRUE(contains(at(errorsOf(zero), "/measurements/0/line").what, "zero-length"));

  const std::string both = with(R"([{"id": "m", "line": [[0,0],[1,1]], "polygon": [[0,0],[1,0],[1,1]]}])");
  EXPECT_TRUE(contains(at(errorsOf(both), "/measurements/0/polygon").what, "a line and an area"));

  const std::string neither = with(R"([{"id": "m"}])");
  EXPECT_TRUE(contains(at(errorsOf(neither), "/measurements/0").what, "no \"line\" or \"polygon\""));

  const std::string noId = with(R"([{"line": [[0,0],[1,1]]}])");
  EXPECT_TRUE(contains(at(errorsOf(noId), "/measurements/0").what, "missing required key \"id\""));

  const std::string crossed = with(R"([{"id": "a", "polygon": [[0,0],[2,2],[2,0],[0,2]]}])");
  EXPECT_TRUE(contains(at(errorsOf(crossed), "/measurements/0/polygon/2").what, "self-intersecting"));

  const std::string twice = with(R"([{"id": "m", "line": [[0,0],[1,1]]}, {"id": "m", "polygon": [[0,0],[1,0],[1,1]]}])");
  const auto d2 = at(errorsOf(twice), "/measurements/1/id");
  expectAt(d2, twice, "\"m\"", 1);
  EXPECT_TRUE(contains(d2.hint, "/measurements/0")) << d2.format();
}

// The scenario key "smoke" (NIST TN 1822 test 2.5): regions of an extinction coefficient that slow
// walking by Frantzich and Nilsson's relation (sim::smokeSpeedFactor).
TEST(ScenarioSmoke, RegionsAreParsedAndSlowWalking) {
  const std::string text = edit(kBottleneck, R"("points": [)", R"("smoke": [
    {"polygon": [[0,0],[20,0],[20,10],[0,10]], "extinction": 6}
  ],
  "points": [)");
  auto r = load(text);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  ASSERT_EQ(r->desc.smoke.size(), 1u);
  EXPECT_EQ(r->desc.smoke[0].polygon.size(), 4u);
  EXPECT_FLOAT_EQ(r->desc.smoke[0].extinction, 6.0f);
  auto plain = load(kBottleneck);
  ASSERT_TRUE(plain.ok());
  EXPECT_NE(runHash(r->desc, 100), runHash(plain->desc, 100)) << "smoke changes how people walk";
  // The relation: v0 (1 − 0.057 / 0.706 · K), never below 0.1 v0.
  EXPECT_FLOAT_EQ(sim::smokeSpeedFactor(0.0f), 1.0f);
  EXPECT_NEAR(sim::smokeSpeedFactor(6.0f), 1.0f - 0.057f / 0.706f * 6.0f, 1e-6f);
  EXPECT_FLOAT_EQ(sim::smokeSpeedFactor(30.0f), 0.1f);
}

TEST(ScenarioSmoke, BadValuesAreLocated) {
  const auto with = [](const std::string& list) { return edit(kBottleneck, R"("points": [)", "\"smoke\": " + list + ",\n  \"points\": ["); };
  const std::string thick = with(R"([{"polygon": [[0,0],[1,0],[1,1]], "extinction": 40}])");
  const auto d1 = at(errorsOf(thick), "/smoke/0/extinction");
  expectAt(d1, thick, "40");
  EXPECT_TRUE(contains(d1.expected, "30")) << d1.format();
  const std::string noPolygon = with(R"([{"extinction": 1}])");
  EXPECT_TRUE(contains(at(errorsOf(noPolygon), "/smoke/0").what, "missing required key \"polygon\""));
  const std::string noK = with(R"([{"polygon": [[0,0],[1,0],[1,1]]}])");
  EXPECT_TRUE(contains(at(errorsOf(noK), "/smoke/0").what, "missing required key \"extinction\""));
  const std::string notList = with(R"({"polygon": [[0,0],[1,0],[1,1]], "extinction": 1})");
  EXPECT_TRUE(contains(at(errorsOf(notList), "/smoke").what, "wrong type")) << "an object, not an array";
  const std::string levels = R"({"format": "throng/1",
 "terrain": {"vertices": [[0,0,0],[10,0,0],[10,0,10],[0,0,10]], "walkable": [0,1,2, 0,2,3]},
 "smoke": [{"polygon": [[0,0],[1,0],[1,1]], "extinction": 1}],
 "populations": []})";
  EXPECT_TRUE(contains(at(errorsOf(levels), "/smoke").what, "multi-level")) << "flat worlds only";
  const std::string deadly = with(R"([{"polygon": [[0,0],[1,0],[1,1]], "extinction": 1, "co": 200000}])");
  const auto d2 = at(errorsOf(deadly), "/smoke/0/co");
  expectAt(d2, deadly, "200000");
  EXPECT_TRUE(contains(d2.expected, "100000")) << d2.format();
  const std::string negative = with(R"([{"polygon": [[0,0],[1,0],[1,1]], "extinction": 1, "co": -5}])");
  EXPECT_TRUE(contains(at(errorsOf(negative), "/smoke/0/co").expected, "0")) << "no negative concentration";
}

// Smoke's carbon monoxide (NIST TN 1822 test 2.6): "co" in ppm, a population's "incapacitationDose"
// (the fractional effective dose at which its people stop, ISO 13571: 1 by default).
TEST(ScenarioSmoke, CarbonMonoxideAndTheIncapacitationDoseAreParsed) {
  std::string text = edit(kBottleneck, R"("points": [)", R"("smoke": [
    {"polygon": [[0,0],[20,0],[20,10],[0,10]], "extinction": 2, "co": 7000}
  ],
  "points": [)");
  auto plain = load(text);
  ASSERT_TRUE(plain.ok()) << core::formatAll(plain.errors());
  EXPECT_FLOAT_EQ(plain->desc.smoke[0].co, 7000.0f);
  EXPECT_FLOAT_EQ(plain->desc.populations[0].incapacitationDose, 1.0f);
  text = edit(text, R"("groups")", R"("incapacitationDose": 0.3, "groups")");
  auto sensitive = load(text);
  ASSERT_TRUE(sensitive.ok()) << core::formatAll(sensitive.errors());
  EXPECT_FLOAT_EQ(sensitive->desc.populations[0].incapacitationDose, 0.3f);
  // ISO 13571: 35 000 ppm for a minute is a dose of 1.
  EXPECT_NEAR(sim::coDosePerSecond(35000.0f) * 60.0f, 1.0f, 1e-6f);
  const std::string zero = edit(text, R"("incapacitationDose": 0.3)", R"("incapacitationDose": 0)");
  const auto d = at(errorsOf(zero), "/populations/0/incapacitationDose");
  expectAt(d, zero, R"(0, "groups")");
  EXPECT_TRUE(contains(d.expected, "10")) << d.format();
}

// The scenario's "description" (for people: what the world is, what to watch; the viewer's HUD shows
// it): a string of at most 1000 bytes.
TEST(ScenarioDescription, IsReadAndBadOnesAreLocated) {
  const std::string text = edit(kBottleneck, R"("seed": 7,)", R"("description": "100 people, one gap.", "seed": 7,)");
  auto r = load(text);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r->desc.description, "100 people, one gap.");
  EXPECT_EQ(load(kBottleneck)->desc.description, "");
  const std::string number = edit(kBottleneck, R"("seed": 7,)", R"("description": 5, "seed": 7,)");
  const auto d = at(errorsOf(number), "/description");
  EXPECT_TRUE(contains(d.what, "wrong type")) << d.format();
  const std::string longer = edit(kBottleneck, R"("seed": 7,)", "\"description\": \"" + std::string(1001, 'a') + "\", \"seed\": 7,");
  const auto d2 = at(errorsOf(longer), "/description");
  EXPECT_TRUE(contains(d2.expected, "1000 bytes")) << d2.format();
}

}  // namespace
// Lifts and escalators ("transports"): the verification scenarios load, with their parameters, and
// the goals beyond a stop count as reached from the other stop (the floors are joined by nothing
// else: without the transport the exit is unreachable and the check says so).
namespace {
std::string fileText(const std::string& rel) {
  std::ifstream in(std::string(THRONG_SOURCE_DIR) + "/" + rel);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST(ScenarioTransports, LiftsAndEscalatorsAreParsedAndCarryPeopleToReachableGoals) {
  const std::string lift = fileText("verification/nist/2.7-elevators.json");
  auto r = load(lift, true);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  ASSERT_EQ(r->desc.transports.size(), 1u);
  const sim::TransportDesc& t = r->desc.transports[0];
  EXPECT_EQ(t.kind, sim::TransportKind::Elevator);
  EXPECT_EQ(r->desc.points[t.stops[0]].id, "lift-low");
  EXPECT_EQ(r->desc.points[t.stops[1]].id, "lift-high");
  EXPECT_EQ(t.capacity, 8u);
  EXPECT_FLOAT_EQ(t.speed, 1.0f);
  EXPECT_FLOAT_EQ(t.transferTime, 1.2f);
  const std::string escalator = fileText("verification/iso/21-escalators.json");
  auto e = load(escalator, true);
  ASSERT_TRUE(e.ok()) << core::formatAll(e.errors());
  EXPECT_EQ(e->desc.transports[0].kind, sim::TransportKind::Escalator);
  EXPECT_FLOAT_EQ(e->desc.transports[0].headway, 0.8f);
  // An elevator without "speed" gets a lift's default, 1 m/s (an escalator's is 0.5).
  const std::string noSpeed = edit(lift, R"("speed": 1.0,)", "");
  ASSERT_NE(noSpeed, lift);
  EXPECT_FLOAT_EQ(load(noSpeed)->desc.transports[0].speed, 1.0f);
  // Without the lift the ground floor's exit cannot be reached from the upper floor.
  const auto cut = lift.find(R"("transports")");
  ASSERT_NE(cut, std::string::npos);
  std::string noLift = lift.substr(0, cut);
  noLift.erase(noLift.find_last_of(','));
  noLift += "\n}\n";
  const auto unreachable = errorsOf(noLift, true);
  EXPECT_TRUE(contains(at(unreachable, "/populations/0/goals/1").what, "cannot be reached")) << core::formatAll(unreachable);
}

TEST(ScenarioTransports, BadTransportsAreLocated) {
  const std::string lift = fileText("verification/nist/2.7-elevators.json");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string s = edit(lift, from, to);
    EXPECT_NE(s, lift) << from;
    return s;
  };
  const std::string kind = with(R"("kind": "elevator")", R"("kind": "elevater")");
  const auto dk = at(errorsOf(kind), "/transports/0/kind");
  expectAt(dk, kind, "\"elevater\"");
  EXPECT_TRUE(contains(dk.hint, "elevator")) << dk.format();
  const std::string same = with(R"("stops": [
    "lift-low",
    "lift-high"
   ])", R"("stops": ["lift-low", "lift-low"])");
  EXPECT_TRUE(contains(at(errorsOf(same), "/transports/0/stops/1").what, "same point")) << same;
  const std::string typo = with(R"("stops": [
    "lift-low",
    "lift-high"
   ])", R"("stops": ["lift-low", "lift-hihg"])");
  EXPECT_TRUE(contains(at(errorsOf(typo), "/transports/0/stops/1").hint, "lift-high"));
  const std::string exitStop = with(R"("stops": [
    "lift-low",
    "lift-high"
   ])", R"("stops": ["lift-low", "exit"])");
  EXPECT_TRUE(contains(at(errorsOf(exitStop), "/transports/0/stops/1").what, "no interest point"));
  const std::string wrongKey = with(R"("capacity": 8,)", R"("capacity": 8, "headway": 1,)");
  EXPECT_TRUE(contains(at(errorsOf(wrongKey), "/transports/0/headway").what, "escalator"));
  const std::string big = with(R"("capacity": 8,)", R"("capacity": 1000,)");
  expectAt(at(errorsOf(big), "/transports/0/capacity"), big, "1000");
  const std::string slow = with(R"("speed": 1.0,)", R"("speed": 0,)");
  EXPECT_TRUE(contains(at(errorsOf(slow), "/transports/0/speed").expected, "0.1"));
  const std::string twice = with(R"("transports": [)", R"("transports": [
  {"id": "lift", "kind": "escalator", "stops": ["lift-high", "lift-low"]},)");
  const auto dd = errorsOf(twice);
  EXPECT_TRUE(contains(at(dd, "/transports/1/id").what, "duplicate")) << core::formatAll(dd);
  EXPECT_TRUE(contains(at(dd, "/transports/1/stops/0").what, "already a stop")) << core::formatAll(dd);
  // An escalator has two stops; a lift may serve more floors (here the exit is no interest point).
  const std::string escalator = fileText("verification/iso/21-escalators.json");
  const std::string three = edit(escalator, R"("escalator-high"
   ],)", R"("escalator-high",
    "exit"
   ],)");
  ASSERT_NE(three, escalator);
  const auto d3 = at(errorsOf(three), "/transports/0/stops");
  EXPECT_TRUE(contains(d3.what, "3 stops")) << d3.format();
  EXPECT_TRUE(contains(d3.expected, "two")) << d3.format();
  const std::string liftThree = with(R"("lift-high"
   ],)", R"("lift-high",
    "exit"
   ],)");
  EXPECT_TRUE(contains(at(errorsOf(liftThree), "/transports/0/stops/2").what, "no interest point"));
}

// People ride of their own accord (useTransports, on by default): a goal that only a lift joins to
// the spawn is reachable though no goal names the lift's stop; with useTransports false it is not,
// and the check says so; a non-boolean is located.
TEST(ScenarioTransports, GoalsBeyondALiftAreReachableForPeopleWhoRideOfTheirOwnAccord) {
  const std::string lift = fileText("verification/nist/2.7-elevators.json");
  const std::string direct = edit(lift, R"("goals": [
    "lift-high",
    "exit"
   ],)", R"("goals": ["exit"],)");
  ASSERT_NE(direct, lift);
  auto r = load(direct, true);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_TRUE(r->desc.populations[0].useTransports);
  const std::string walkers = edit(direct, R"("goals": ["exit"],)", R"("goals": ["exit"], "useTransports": false,)");
  EXPECT_FALSE(load(walkers)->desc.populations[0].useTransports);
  const auto unreachable = at(errorsOf(walkers, true), "/populations/0/goals/0");
  EXPECT_TRUE(contains(unreachable.what, "cannot be reached")) << unreachable.format();
  const std::string number = edit(direct, R"("goals": ["exit"],)", R"("goals": ["exit"], "useTransports": 1,)");
  const auto d = at(errorsOf(number), "/populations/0/useTransports");
  expectAt(d, number, "1,\n   \"speed\"");
  EXPECT_TRUE(contains(d.what, "wrong type")) << d.format();
}

}  // namespace throng::io::test

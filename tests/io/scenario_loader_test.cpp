// Tests for libs/io/src/scenario_loader.cpp and scenario_parser.cpp: valid scenarios load with the
// right values (defaults, both windings, group size ranges, every spawn form, every point kind).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

TEST(ScenarioLoader, BottleneckExampleLoads) {
  auto r = load(kBottleneck);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r->desc;
  EXPECT_EQ(d.format, "throng/1");
  EXPECT_EQ(d.name, "bottleneck");
  EXPECT_EQ(d.seed, 7u);
  EXPECT_FLOAT_EQ(d.duration, 300.0f);
  EXPECT_FLOAT_EQ(d.dt, 0.05f);  // default
  ASSERT_EQ(d.walkable.size(), 1u);
  ASSERT_EQ(d.obstacles.size(), 2u);
  ASSERT_EQ(d.points.size(), 2u);
  EXPECT_EQ(d.points[0].id, "gap");
  EXPECT_EQ(d.points[0].kind, sim::PointKind::Interest);
  EXPECT_EQ(d.points[0].position, core::Vec2(9.5f, 5.0f));
  EXPECT_FLOAT_EQ(d.points[0].radius, 0.5f);
  EXPECT_EQ(d.points[1].kind, sim::PointKind::Exit);
  EXPECT_EQ(d.points[1].polygon.size(), 4u);
  EXPECT_NEAR(d.points[1].position.x, 19.5f, 1e-5);  // polygon centroid
  EXPECT_NEAR(d.points[1].position.y, 5.0f, 1e-5);
  ASSERT_EQ(d.populations.size(), 1u);
  const sim::PopulationDesc& p = d.populations[0];
  EXPECT_EQ(p.id, "crowd");
  EXPECT_EQ(p.groups, 100u);
  EXPECT_EQ(p.sizeMin, 1u);
  EXPECT_EQ(p.sizeMax, 1u);
  EXPECT_EQ(p.spawn.kind, sim::SpawnKind::Polygon);
  EXPECT_EQ(p.spawn.polygon.size(), 4u);
  EXPECT_EQ(p.goals, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_FLOAT_EQ(p.speedMean, 1.34f);
  EXPECT_FLOAT_EQ(p.speedSd, 0.26f);
  EXPECT_FLOAT_EQ(p.speedMin, 0.3f);
  EXPECT_FLOAT_EQ(p.speedMax, 2.5f);
  EXPECT_FLOAT_EQ(p.radius, 0.2f);
  EXPECT_FALSE(p.wander);
  EXPECT_TRUE(d.hasExit());
  EXPECT_FLOAT_EQ(d.maxRadius(), 0.2f);
  EXPECT_EQ(r->text, kBottleneck);
  EXPECT_EQ(r->navmesh, nullptr);  // no reachability check asked for
}

TEST(ScenarioLoader, MinimalScenarioGetsDefaults) {
  auto r = load(R"({"format": "throng/1", "walkable": [[[0,0],[10,0],[10,10],[0,10]]],
    "populations": [{"spawn": {"position": [5, 5]}}]})");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r->desc;
  EXPECT_EQ(d.seed, 1u);
  EXPECT_FLOAT_EQ(d.duration, 300.0f);
  EXPECT_FALSE(d.hasExit());
  const sim::PopulationDesc& p = d.populations[0];
  EXPECT_EQ(p.id, "population0");
  EXPECT_EQ(p.groups, 1u);
  EXPECT_EQ(p.spawn.kind, sim::SpawnKind::Position);
  EXPECT_EQ(p.spawn.position, core::Vec2(5, 5));
  EXPECT_TRUE(p.goals.empty());
  EXPECT_FLOAT_EQ(p.speedMean, 1.34f);
  EXPECT_FLOAT_EQ(p.radius, 0.2f);
}

TEST(ScenarioLoader, BothWindingsAndClosingVertex) {
  // Clockwise walkable, closing vertex repeated (GeoJSON style), clockwise spawn.
  auto r = load(R"({"format": "throng/1",
    "walkable": [[[0,0],[0,10],[10,10],[10,0],[0,0]]],
    "populations": [{"groups": 5, "spawn": {"polygon": [[1,1],[1,3],[3,3],[3,1]]}}]})");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r->desc.walkable[0].size(), 4u);
  EXPECT_LT(core::signedArea(r->desc.walkable[0]), 0.0);  // kept as written
}

TEST(ScenarioLoader, GroupSizeRangeSpeedNumberAndExtras) {
  auto r = load(R"({"format": "throng/1", "dt": 0.02, "navCellSize": 0.1,
    "steering": {"timeHorizon": 3, "timeHorizonObstacle": 1, "neighbourDistance": 5, "maxNeighbours": 16, "accelerationTime": 0.4},
    "walkable": [[[0,0],[30,0],[30,30],[0,30]]],
    "points": [{"id": "bench", "kind": "action", "position": [20, 20], "radius": 3, "stop": false,
                "orientation": [0, 2], "action": "sit", "duration": 12.5}],
    "populations": [{"id": "fam", "groups": 10, "size": [2, 4], "spawn": {"point": "bench"}, "start": 5,
                     "speed": 1.1, "radius": 0.25, "wander": true},
                    {"id": "solo", "speed": {"mean": 1.2, "sd": 0.1, "min": 0.5, "max": 1.8},
                     "spawn": {"polygon": [[1,1],[9,1],[9,9],[1,9]]}, "goals": ["bench"]}]})");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r->desc;
  EXPECT_FLOAT_EQ(d.dt, 0.02f);
  EXPECT_FLOAT_EQ(d.navCellSize, 0.1f);
  EXPECT_FLOAT_EQ(d.steering.timeHorizon, 3.0f);
  EXPECT_FLOAT_EQ(d.steering.timeHorizonObstacle, 1.0f);
  EXPECT_FLOAT_EQ(d.steering.neighbourDistance, 5.0f);
  EXPECT_EQ(d.steering.maxNeighbours, 16u);
  EXPECT_FLOAT_EQ(d.steering.accelerationTime, 0.4f);
  const sim::PointDesc& bench = d.points[0];
  EXPECT_EQ(bench.kind, sim::PointKind::Action);
  EXPECT_FALSE(bench.stop);
  EXPECT_EQ(bench.orientation, core::Vec2(0, 1));  // normalised
  EXPECT_EQ(bench.action, "sit");
  EXPECT_FLOAT_EQ(bench.actionDuration, 12.5f);
  const sim::PopulationDesc& fam = d.populations[0];
  EXPECT_EQ(fam.sizeMin, 2u);
  EXPECT_EQ(fam.sizeMax, 4u);
  EXPECT_EQ(fam.spawn.kind, sim::SpawnKind::Point);
  EXPECT_EQ(fam.spawn.point, 0u);
  EXPECT_FLOAT_EQ(fam.start, 5.0f);
  EXPECT_FLOAT_EQ(fam.speedMean, 1.1f);
  EXPECT_FLOAT_EQ(fam.speedSd, 0.0f);
  EXPECT_FLOAT_EQ(fam.radius, 0.25f);
  EXPECT_TRUE(fam.wander);
  const sim::PopulationDesc& solo = d.populations[1];
  EXPECT_FLOAT_EQ(solo.speedMin, 0.5f);
  EXPECT_FLOAT_EQ(solo.speedMax, 1.8f);
  EXPECT_EQ(solo.goals, std::vector<std::uint32_t>{0});
  EXPECT_FLOAT_EQ(d.maxRadius(), 0.25f);
}

TEST(ScenarioLoader, ActionPointStopsByDefault) {
  auto r = load(R"({"format": "throng/1", "walkable": [[[0,0],[10,0],[10,10],[0,10]]],
    "points": [{"id": "a", "kind": "action", "polygon": [[1,1],[2,1],[2,2],[1,2]]}],
    "populations": []})");
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_TRUE(r->desc.points[0].stop);
  EXPECT_EQ(r->desc.points[0].orientation, core::Vec2(1, 0));
}

TEST(ScenarioLoader, LoadsFileAndNamesUnreadableOne) {
  const std::string path = std::string(THRONG_BINARY_DIR) + "/scenario_loader_test.json";
  {
    std::ofstream out(path, std::ios::binary);
    out << kBottleneck;
  }
  auto r = io::loadScenarioFile(path, io::LoadOptions{false});
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r->desc.populations[0].groups, 100u);
  std::remove(path.c_str());
  auto missing = io::loadScenarioFile(path + ".missing");
  ASSERT_FALSE(missing.ok());
  ASSERT_EQ(missing.errors().size(), 1u);
  EXPECT_EQ(missing.errors()[0].source, path + ".missing");
  EXPECT_NE(missing.errors()[0].what.find("cannot open file"), std::string::npos);
}

// Tests for throng::nav::NavMesh (libs/nav/src/navmesh.cpp, tile_builder.cpp, walkable_raster.cpp):
// erosion, doors, concave and overlapping input, diagnostics, multi-tile worlds.
#include <gtest/gtest.h>

#include "nav_test_worlds.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {
namespace {
using testing::buildOrFail;
using testing::rect;

TEST(NavMesh, BuildsRoomAndReportsBoundsAndPolygons) {
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, {});
  ASSERT_TRUE(mesh);
  EXPECT_GT(mesh->polygonCount(), 0u);
  EXPECT_EQ(mesh->polygons().size(), mesh->polygonCount());
  EXPECT_FLOAT_EQ(mesh->bounds().min.x, 0.0f);
  EXPECT_FLOAT_EQ(mesh->bounds().max.y, 10.0f);
  EXPECT_FLOAT_EQ(mesh->config().cellSize, 0.05f);  // agentRadius / 4 (automatic)
  for (const Polygon& poly : mesh->polygons()) {
    EXPECT_GE(poly.size(), 3u);
    for (Vec2 p : poly) {
      EXPECT_GE(p.x, 0.1f);  // eroded by the radius (0.2 m), within a cell
      EXPECT_LE(p.x, 19.9f);
      EXPECT_GE(p.y, 0.1f);
      EXPECT_LE(p.y, 9.9f);
    }
  }
}

TEST(NavMesh, ErosionKeepsMeshAtLeastRadiusFromWalls) {
  const float radius = 0.2f;
  NavMeshConfig cfg;
  cfg.agentRadius = radius;
  auto mesh = buildOrFail({rect(0, 0, 10, 10)}, {rect(4, 4, 6, 6)}, cfg);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  const float tolerance = mesh->config().cellSize;
  // Points on the outer wall and on the block's faces snap at least ~radius away.
  struct Probe { Vec2 p; Vec2 wallPoint; };
  const Probe probes[] = {{{0.0f, 5.0f}, {0.0f, 5.0f}}, {{10.0f, 2.0f}, {10.0f, 2.0f}}, {{3.0f, 10.0f}, {3.0f, 10.0f}},
                          {{4.0f, 5.0f}, {4.0f, 5.0f}}, {{5.0f, 6.0f}, {5.0f, 6.0f}}, {{6.0f, 4.5f}, {6.0f, 4.5f}}};
  for (const Probe& probe : probes) {
    auto hit = query.nearest(probe.p, 1.0f);
    ASSERT_TRUE(hit) << probe.p.x << "," << probe.p.y;
    EXPECT_GE(distance(hit->first, probe.wallPoint), radius - tolerance) << probe.p.x << "," << probe.p.y;
    EXPECT_LE(distance(hit->first, probe.wallPoint), radius + 2.0f * tolerance) << probe.p.x << "," << probe.p.y;
  }
  // No mesh inside the block.
  EXPECT_FALSE(query.nearest({5.0f, 5.0f}, 0.5f));
}

TEST(NavMesh, DoorOfOneMetreStaysPassable) {
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, testing::doorWall(1.0f));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  EXPECT_EQ(query.findPath({2, 2}, {18, 8}, corners), PathStatus::Complete);
  EXPECT_TRUE(query.reachable({2, 2}, {18, 8}));
}

TEST(NavMesh, DoorNarrowerThanTheAgentIsClosed) {
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, testing::doorWall(0.3f));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  EXPECT_EQ(query.findPath({2, 5}, {18, 5}, corners), PathStatus::Partial);
  ASSERT_FALSE(corners.empty());
  EXPECT_LT(corners.back().x, 10.0f);  // ends on the near side of the wall
  EXPECT_FALSE(query.reachable({2, 5}, {18, 5}));
}

TEST(NavMesh, NarrowCorridor) {
  auto mesh = buildOrFail({rect(0, 0, 40, 2)}, {});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  ASSERT_EQ(query.findPath({1, 1}, {39, 1}, corners), PathStatus::Complete);
  EXPECT_NEAR(corners.back().x, 39.0f, 1e-3f);
}

TEST(NavMesh, ConcaveAndOverlappingWalkablePolygonsUnite) {
  // An L made of two overlapping rectangles, plus a concave U polygon touching it.
  const std::vector<Polygon> walkable = {rect(0, 0, 10, 3), rect(7, 0, 10, 10),
                                         Polygon{{10, 0}, {16, 0}, {16, 10}, {14, 10}, {14, 2}, {12, 2}, {12, 10}, {10, 10}}};
  auto mesh = buildOrFail(walkable, {});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  EXPECT_TRUE(query.reachable({1, 1.5f}, {8.5f, 9}));
  EXPECT_TRUE(query.reachable({1, 1.5f}, {15, 9}));
  EXPECT_FALSE(query.nearest({13, 6}, 0.5f));  // inside the U's notch
}

TEST(NavMesh, NothingWalkableAfterErosionIsADiagnostic) {
  NavMeshConfig cfg;
  cfg.agentRadius = 0.5f;
  auto result = NavMesh::build(std::vector<Polygon>{rect(0, 0, 10, 0.6f)}, {}, cfg);
  ASSERT_FALSE(result.ok());
  ASSERT_EQ(result.errors().size(), 1u);
  EXPECT_NE(result.errors()[0].what.find("nothing walkable remains"), std::string::npos);
  EXPECT_NE(result.errors()[0].expected.find("1 m"), std::string::npos);
}

TEST(NavMesh, BadInputReportsEveryProblem) {
  NavMeshConfig cfg;
  cfg.agentRadius = -1.0f;
  const std::vector<Polygon> walkable = {Polygon{{0, 0}, {1, 0}}};
  auto result = NavMesh::build(walkable, std::vector<Polygon>{Polygon{}}, cfg);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.errors().size(), 3u) << core::formatAll(result.errors());
  EXPECT_FALSE(NavMesh::build({}, {}, {}).ok());
}

TEST(NavMesh, LargeWorldHasManyTilesAndPathsCrossThem) {
  NavMeshConfig cfg;
  cfg.cellSize = 0.2f;  // keep the test fast
  auto mesh = buildOrFail({rect(0, 0, 300, 300)}, testing::pillars(300, 10), cfg);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  const Vec2 from{2, 3};
  const Vec2 to{297, 296};
  ASSERT_EQ(query.findPath(from, to, corners), PathStatus::Complete);
  EXPECT_NEAR(corners.back().x, to.x, 1e-3f);
  EXPECT_NEAR(corners.back().y, to.y, 1e-3f);
  // Tiles are 48 m: a diagonal across 300 m crosses at least 6 tile borders; the path is short.
  EXPECT_LT(testing::pathLength(from, corners), distance(from, to) * 1.05f);
  EXPECT_GT(mesh->polygonCount(), 49u);
  // Pillars are avoided.
  EXPECT_FALSE(query.nearest({150, 150}, 0.5f));
}

TEST(NavMesh, BuildIsDeterministic) {
  auto a = buildOrFail({rect(0, 0, 60, 60)}, testing::pillars(60, 7));
  auto b = buildOrFail({rect(0, 0, 60, 60)}, testing::pillars(60, 7));
  ASSERT_TRUE(a && b);
  const auto pa = a->polygons();
  const auto pb = b->polygons();
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) EXPECT_EQ(pa[i], pb[i]);
}

// The walls keep their polygon's winding: the walkable side of every boundary segment is on the
// right of a → b, round the room's outline and round an obstacle alike (the anticipation model's
// room measure relies on it: a step towards that side is never blocked).
TEST(NavMesh, BoundarySegmentsHaveTheWalkableSideOnTheirRight) {
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, {rect(8, 4, 12, 6)});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  const auto walls = mesh->boundary();
  ASSERT_GE(walls.size(), 8u);
  int checked = 0;
  for (const core::Segment& w : walls) {
    const Vec2 e = w.b - w.a;
    const float len = core::length(e);
    if (len < 0.3f) continue;  // a corner's cut: too short to step off its middle reliably
    const Vec2 right{e.y / len, -e.x / len};
    const Vec2 mid = (w.a + w.b) * 0.5f;
    const auto in = query.nearest(mid + right * 0.05f, 0.5f);
    const auto out = query.nearest(mid - right * 0.05f, 0.5f);
    ASSERT_TRUE(in && out);
    EXPECT_LT(core::length(in->first - (mid + right * 0.05f)), 1e-3f) << "right of the wall is walkable";
    EXPECT_GT(core::length(out->first - (mid - right * 0.05f)), 0.03f) << "left of the wall is not";
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

}  // namespace
}  // namespace throng::nav

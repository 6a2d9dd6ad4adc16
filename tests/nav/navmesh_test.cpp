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

// Cut regions (NavMeshConfig::cuts, NavMesh::setClosed): a closed door is a wall. Two rooms joined
// by two 1 m doors at y 2.5 and 7.5 in a 0.2 m wall at x 10; the south door is cut.
namespace throng::nav::cut_test {
using testing::buildOrFail;
using testing::insideRect;
using testing::rect;

std::shared_ptr<NavMesh> twoRooms() {
  NavMeshConfig cfg;
  CutRegion door;
  door.polygon = rect(9.7f, 2.0f, 10.5f, 3.0f);
  cfg.cuts = {door};
  auto mesh = buildOrFail({rect(0, 0, 10, 10), rect(10.2f, 0, 20, 10), rect(10, 2, 10.2f, 3), rect(10, 7, 10.2f, 8)},
                          {}, cfg);
  return mesh ? mesh->clone() : nullptr;
}

/// The most y of a path's corners (the north door is at y 7..8, the south one at 2..3).
float highest(const std::vector<Vec2>& corners) {
  float y = 0.0f;
  for (Vec2 c : corners) y = std::max(y, c.y);
  return y;
}

TEST(NavMeshCut, ACutRegionIsPolygonsOfItsOwnWhichCloseAndOpen) {
  auto mesh = twoRooms();
  ASSERT_TRUE(mesh);
  const auto polys = mesh->cutPolygons(mesh->config().cuts[0]);
  ASSERT_FALSE(polys.empty());
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  // Open: from the south of the west room to the south of the east room through the south door.
  ASSERT_EQ(query.findPath({5, 2.5f}, {15, 2.5f}, corners), PathStatus::Complete);
  EXPECT_LT(highest(corners), 3.5f);
  mesh->setClosed(polys, true);
  ASSERT_EQ(query.findPath({5, 2.5f}, {15, 2.5f}, corners), PathStatus::Complete);
  EXPECT_GT(highest(corners), 6.5f) << "the path ran through the closed south door";
  // Walking into the closed door stops at its edge; nothing snaps into it.
  PolyRef ref = 0;
  Vec2 p{9.0f, 2.5f};
  for (int i = 0; i < 40; ++i) p = query.moveAlongSurface(p, p + Vec2{0.1f, 0.0f}, ref);
  EXPECT_LT(p.x, 9.76f);
  const auto snapped = query.nearest({10.1f, 2.5f}, 2.0f);
  ASSERT_TRUE(snapped);
  EXPECT_FALSE(insideRect(snapped->first, 9.76f, 2.06f, 10.44f, 2.94f));  // the door less a cell
  mesh->setClosed(polys, false);
  ASSERT_EQ(query.findPath({5, 2.5f}, {15, 2.5f}, corners), PathStatus::Complete);
  EXPECT_LT(highest(corners), 3.5f);
}

TEST(NavMeshCut, ACloneClosesItsDoorsAlone) {
  auto mesh = twoRooms();
  ASSERT_TRUE(mesh);
  auto copy = mesh->clone();
  EXPECT_EQ(copy->polygonCount(), mesh->polygonCount());
  copy->setClosed(copy->cutPolygons(copy->config().cuts[0]), true);
  NavQuery original(mesh), closed(copy);
  std::vector<Vec2> corners;
  ASSERT_EQ(original.findPath({5, 2.5f}, {15, 2.5f}, corners), PathStatus::Complete);
  EXPECT_LT(highest(corners), 3.5f);
  ASSERT_EQ(closed.findPath({5, 2.5f}, {15, 2.5f}, corners), PathStatus::Complete);
  EXPECT_GT(highest(corners), 6.5f);
}

TEST(NavMeshCut, WithoutCutsTheMeshIsAsBefore) {
  NavMeshConfig cfg;
  auto plain = buildOrFail({rect(0, 0, 20, 10)}, {}, cfg);
  ASSERT_TRUE(plain);
  CutRegion far;
  far.centre = {100, 100};
  far.radius = 1;
  cfg.cuts = {far};  // outside the world: marks nothing
  auto withFar = buildOrFail({rect(0, 0, 20, 10)}, {}, cfg);
  ASSERT_TRUE(withFar);
  EXPECT_EQ(plain->polygons(), withFar->polygons());
  EXPECT_TRUE(withFar->cutPolygons(far).empty());
}

}  // namespace throng::nav::cut_test

// Tests for throng::nav::NavMesh::buildFromTerrain (libs/nav/src/terrain_builder.cpp,
// terrain_tile.cpp) and the height-taking NavQuery / PathQueue overloads (nav_query.cpp,
// path_queue.cpp): two floors above each other joined by a ramp or stairs, obstacles, diagnostics,
// and that the overloads on a flat mesh answer exactly as the plain queries; stairs: their area and
// gradient (NavMesh::surface) and their route cost (PathQueue cost classes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "nav_test_worlds.hpp"
#include "throng/core/diagnostic.hpp"
#include "throng/nav/distance_field.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"

namespace throng::nav {
namespace {
using testing::buildOrFail;
using testing::rect;

constexpr float kHeightTolerance = 0.15f;  // half a cell height (0.1 m) plus the detail mesh's error

/// Writes triangles into a TerrainMesh (scenario coordinates, z up).
struct TerrainWriter {
  TerrainMesh mesh;

  std::uint32_t vertex(float x, float y, float z) {
    mesh.vertices.insert(mesh.vertices.end(), {x, y, z});
    return static_cast<std::uint32_t>(mesh.vertices.size() / 3 - 1);
  }
  // Quad a-b-c-d as two triangles.
  void quad(std::vector<std::uint32_t>& out, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    out.insert(out.end(), {a, b, c, a, c, d});
  }
  /// Horizontal walkable rectangle at height z (wound clockwise from above, to test any winding).
  void floor(float x0, float y0, float x1, float y1, float z) {
    quad(mesh.walkable, vertex(x0, y0, z), vertex(x0, y1, z), vertex(x1, y1, z), vertex(x1, y0, z));
  }
  /// Walkable ramp over [x0,x1]x[y0,y1] rising along x from z0 to z1.
  void rampX(float x0, float x1, float y0, float y1, float z0, float z1) {
    quad(mesh.walkable, vertex(x0, y0, z0), vertex(x1, y0, z1), vertex(x1, y1, z1), vertex(x0, y1, z0));
  }
  /// Staircase over [x0, ...]x[y0,y1] from z0 up along x: `steps` treads `depth` deep, `rise` high.
  void stairsX(float x0, float y0, float y1, float z0, int steps, float depth, float rise) {
    for (int i = 0; i < steps; ++i) {
      const float xa = x0 + static_cast<float>(i) * depth;
      const float z = z0 + static_cast<float>(i + 1) * rise;
      floor(xa, y0, xa + depth, y1, z);
      // Riser: vertical, so never walkable; rasterised as solid.
      quad(mesh.walkable, vertex(xa, y0, z - rise), vertex(xa, y1, z - rise), vertex(xa, y1, z), vertex(xa, y0, z));
    }
  }
  /// Solid box (obstacle triangles, all six faces).
  void box(float x0, float y0, float z0, float x1, float y1, float z1) {
    const std::uint32_t v[8] = {vertex(x0, y0, z0), vertex(x1, y0, z0), vertex(x1, y1, z0), vertex(x0, y1, z0),
                                vertex(x0, y0, z1), vertex(x1, y0, z1), vertex(x1, y1, z1), vertex(x0, y1, z1)};
    auto& o = mesh.obstacles;
    quad(o, v[0], v[1], v[2], v[3]);  // bottom
    quad(o, v[4], v[5], v[6], v[7]);  // top
    quad(o, v[0], v[1], v[5], v[4]);
    quad(o, v[1], v[2], v[6], v[5]);
    quad(o, v[2], v[3], v[7], v[6]);
    quad(o, v[3], v[0], v[4], v[7]);
  }
};

/// Ground floor 20 x 10 m at z = 0 and an upper floor (a slab, top at z = 3) right above it; along
/// y in [10, 12]: a landing at z = 0 (x < 5), a 10 m ramp up to z = 3 (x in [5, 15]) and a landing
/// at z = 3 (x > 15).
TerrainMesh twoFloors(bool withRamp) {
  TerrainWriter w;
  w.floor(0, 0, 20, 10, 0);
  w.floor(0, 0, 20, 10, 3);
  if (withRamp) {
    w.floor(0, 10, 5, 12, 0);
    w.rampX(5, 15, 10, 12, 0, 3);
    w.floor(15, 10, 20, 12, 3);
  }
  return w.mesh;
}

std::shared_ptr<const NavMesh> buildTerrainOrFail(const TerrainMesh& terrain, NavMeshConfig config = {}) {
  auto result = NavMesh::buildFromTerrain(terrain, config);
  if (!result.ok()) {
    ADD_FAILURE() << core::formatAll(result.errors());
    return nullptr;
  }
  return result.value();
}

bool hasPointer(const core::Diagnostics& errors, const std::string& pointer) {
  return std::any_of(errors.begin(), errors.end(), [&](const core::Diagnostic& d) { return d.pointer == pointer; });
}

TEST(Terrain, TwoFloorsAreLayeredAndSnapPicksTheLevel) {
  auto mesh = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(mesh);
  EXPECT_TRUE(mesh->layered());
  EXPECT_NEAR(mesh->minHeight(), 0.0f, kHeightTolerance);
  EXPECT_NEAR(mesh->maxHeight(), 3.0f, kHeightTolerance);
  EXPECT_FLOAT_EQ(mesh->config().cellSize, 0.05f);  // automatic, as for flat meshes
  NavQuery query(mesh);
  const auto ground = query.snap({5, 5}, 0.0f);
  const auto upper = query.snap({5, 5}, 3.0f);
  ASSERT_TRUE(ground);
  ASSERT_TRUE(upper);
  EXPECT_NEAR(ground->height, 0.0f, kHeightTolerance);
  EXPECT_NEAR(upper->height, 3.0f, kHeightTolerance);
  EXPECT_NE(ground->ref, upper->ref);
  EXPECT_NEAR(ground->p.x, 5.0f, 1e-3f);
  EXPECT_NEAR(upper->p.y, 5.0f, 1e-3f);
  // A rough hint is enough: within kLevelSearch of the floor.
  const auto hinted = query.snap({5, 5}, 2.2f);
  ASSERT_TRUE(hinted);
  EXPECT_EQ(hinted->ref, upper->ref);
  EXPECT_NEAR(query.heightAt(ground->ref, {5, 5}), 0.0f, kHeightTolerance);
  EXPECT_NEAR(query.heightAt(upper->ref, {6, 4}), 3.0f, kHeightTolerance);
  // Nothing walkable 10 m up.
  EXPECT_FALSE(query.snap({5, 5}, 10.0f));
}

TEST(Terrain, RampHeightsFollowTheSlope) {
  auto mesh = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  for (const float x : {7.0f, 10.0f, 13.0f}) {
    const float expected = 0.3f * (x - 5.0f);
    const auto hit = query.snap({x, 11}, expected);
    ASSERT_TRUE(hit) << x;
    EXPECT_NEAR(hit->height, expected, kHeightTolerance) << x;
    EXPECT_NEAR(query.heightAt(hit->ref, {x, 11}), expected, kHeightTolerance) << x;
  }
}

TEST(Terrain, PathFromGroundToUpperFloorTakesTheRamp) {
  auto mesh = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  ASSERT_EQ(query.findPath({2, 5}, 0.0f, {2, 5}, 3.0f, corners), PathStatus::Complete);
  ASSERT_FALSE(corners.empty());
  EXPECT_NEAR(corners.back().x, 2.0f, 1e-3f);
  EXPECT_NEAR(corners.back().y, 5.0f, 1e-3f);
  // The only way up is the ramp's top end (x > ~13.8 at y >= 10): the path turns there.
  const bool viaRamp = std::any_of(corners.begin(), corners.end(), [](Vec2 c) { return c.x > 12.5f && c.y > 9.0f; });
  EXPECT_TRUE(viaRamp);
  EXPECT_GT(testing::pathLength({2, 5}, corners), 20.0f);
  for (Vec2 c : corners) {
    EXPECT_GE(c.x, 0.0f);
    EXPECT_LE(c.x, 20.0f);
    EXPECT_GE(c.y, 0.0f);
    EXPECT_LE(c.y, 12.0f);
  }
  EXPECT_TRUE(query.reachable({2, 5}, 0.0f, {18, 2}, 3.0f));
  EXPECT_TRUE(query.reachable({18, 2}, 3.0f, {2, 5}, 0.0f));
  // Same level: straight across.
  ASSERT_EQ(query.findPath({2, 5}, 3.0f, {18, 5}, 3.0f, corners), PathStatus::Complete);
  EXPECT_EQ(corners.size(), 1u);

  // The time-sliced queue gives the same path.
  PathQueue queue(mesh);
  const PathTicket ticket = queue.request({2, 5}, 0.0f, {2, 5}, 3.0f);
  while (queue.state(ticket) == TicketState::Pending) queue.update(64);
  const PathResult queued = queue.take(ticket);
  std::vector<Vec2> direct;
  ASSERT_EQ(query.findPath({2, 5}, 0.0f, {2, 5}, 3.0f, direct), PathStatus::Complete);
  EXPECT_EQ(queued.status, PathStatus::Complete);
  ASSERT_EQ(queued.corners.size(), direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(queued.corners[i].x, direct[i].x);
    EXPECT_EQ(queued.corners[i].y, direct[i].y);
  }
}

TEST(Terrain, SmallTilesJoinOnBothLevels) {
  NavMeshConfig cfg;
  cfg.tileSize = 5.0f;  // 4 x 3 tiles: floors, ramp and landings cross tile edges
  auto mesh = buildTerrainOrFail(twoFloors(true), cfg);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  ASSERT_EQ(query.findPath({1, 1.5f}, 0.0f, {19, 8.5f}, 0.0f, corners), PathStatus::Complete);
  EXPECT_EQ(corners.size(), 1u);  // straight across the ground floor's tiles
  ASSERT_EQ(query.findPath({1, 8}, 3.0f, {19, 1.5f}, 3.0f, corners), PathStatus::Complete);
  EXPECT_EQ(corners.size(), 1u);
  ASSERT_EQ(query.findPath({2, 5}, 0.0f, {2, 5}, 3.0f, corners), PathStatus::Complete);
  EXPECT_TRUE(std::any_of(corners.begin(), corners.end(), [](Vec2 c) { return c.x > 12.5f && c.y > 9.0f; }));
  const auto ramp = query.snap({10, 11}, 1.5f);
  ASSERT_TRUE(ramp);
  EXPECT_NEAR(ramp->height, 1.5f, kHeightTolerance);
}

TEST(Terrain, StairsConnectFloors) {
  TerrainWriter w;
  w.floor(0, 0, 10, 4, 0);
  // 12 steps of 0.25 m by 0.35 m from x = 10 up to 3 m at x = 14.2, then the upper floor.
  w.stairsX(10, 0, 2, 0, 12, 0.35f, 0.25f);
  w.floor(14.2f, 0, 24, 4, 3);
  auto mesh = buildTerrainOrFail(w.mesh);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  const auto mid = query.snap({12.0f, 1.0f}, 1.5f);
  ASSERT_TRUE(mid);
  // On the sixth tread (1.5 m); the detail mesh smooths the steps towards a slope.
  EXPECT_NEAR(mid->height, 1.5f, 0.3f);
  std::vector<Vec2> corners;
  EXPECT_EQ(query.findPath({2, 2}, 0.0f, {20, 2}, 3.0f, corners), PathStatus::Complete);
  // Steps higher than maxClimb cannot be climbed.
  NavMeshConfig low;
  low.maxClimb = 0.15f;
  auto steep = buildTerrainOrFail(w.mesh, low);
  ASSERT_TRUE(steep);
  NavQuery steepQuery(steep);
  EXPECT_FALSE(steepQuery.reachable({2, 2}, 0.0f, {20, 2}, 3.0f));
}

/// A point's ground (snapped at about `height`), or flat floor with a test failure off the mesh.
Surface groundAt(const NavMesh& mesh, Vec2 p, float height) {
  NavQuery query(std::shared_ptr<const NavMesh>(&mesh, [](const NavMesh*) {}));
  const auto at = query.snap(p, height);
  if (!at) {
    ADD_FAILURE() << "(" << p.x << ", " << p.y << ") at " << height << " m is off the mesh";
    return {};
  }
  return mesh.surface(at->ref);
}

TEST(Terrain, StairsAreStairAreaWithTheirPitch) {
  TerrainWriter w;
  w.floor(0, 0, 10, 4, 0);
  // 12 steps of 0.25 m on 0.35 m treads (35.5°, rise 0.714 m per metre) from x = 10 to 14.2.
  w.stairsX(10, 0, 4, 0, 12, 0.35f, 0.25f);
  w.floor(14.2f, 0, 24, 4, 3);
  auto mesh = buildTerrainOrFail(w.mesh);
  ASSERT_TRUE(mesh);
  for (const float x : {11.5f, 12.1f, 12.8f}) {
    const Surface stair = groundAt(*mesh, {x, 2.0f}, (x - 10.0f) / 0.35f * 0.25f);
    EXPECT_TRUE(stair.stair) << "x = " << x;
    EXPECT_NEAR(stair.gradient.x, 0.25f / 0.35f, 0.15f) << "x = " << x;
    EXPECT_NEAR(stair.gradient.y, 0.0f, 0.1f) << "x = " << x;
  }
  for (const auto& [p, z] : {std::pair{Vec2{4, 2}, 0.0f}, std::pair{Vec2{20, 2}, 3.0f}}) {
    const Surface floor = groundAt(*mesh, p, z);
    EXPECT_FALSE(floor.stair) << "x = " << p.x;
    EXPECT_NEAR(floor.gradient.x, 0.0f, 0.02f);
  }
}

TEST(Terrain, RampsAreStairsOnlyAboveTheStairSlope) {
  // The ramp of twoFloors: 3 m over 10 m, 16.7°.
  auto steep = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(steep);
  const Surface ramp = groundAt(*steep, {10, 11}, 1.5f);
  EXPECT_TRUE(ramp.stair);
  EXPECT_NEAR(ramp.gradient.x, 0.3f, 0.05f);
  NavMeshConfig gentle;
  gentle.stairSlopeDeg = 20.0f;  // the same ramp is walked as level ground
  auto flat = buildTerrainOrFail(twoFloors(true), gentle);
  ASSERT_TRUE(flat);
  const Surface walkway = groundAt(*flat, {10, 11}, 1.5f);
  EXPECT_FALSE(walkway.stair);
  EXPECT_NEAR(walkway.gradient.x, 0.3f, 0.05f);
  gentle.stairSlopeDeg = 90.0f;
  auto bad = NavMesh::buildFromTerrain(twoFloors(true), gentle);
  ASSERT_FALSE(bad.ok());
  EXPECT_TRUE(hasPointer(bad.errors(), "/stairSlopeDeg"));
}

/// A lower floor (z 0) and an upper one (z 2) joined two ways: a staircase (y 0..2: 8 steps of
/// 0.25 m on 0.3 m treads, 40°) and, 4 m further along y (y 4..6), a 12 m ramp (9.5°, level ground).
TerrainMesh stairOrRamp() {
  TerrainWriter w;
  w.floor(0, 0, 10, 6, 0);
  w.stairsX(10, 0, 2, 0, 8, 0.3f, 0.25f);
  w.floor(12.4f, 0, 22, 2, 2);
  w.rampX(10, 22, 4, 6, 0, 2);
  w.floor(22, 0, 30, 6, 2);
  return w.mesh;
}

TEST(Terrain, DearStairsMakeRoutesTakeTheRamp) {
  auto mesh = buildTerrainOrFail(stairOrRamp());
  ASSERT_TRUE(mesh);
  PathQueue queue(mesh);
  EXPECT_EQ(queue.costClasses(), 0u);
  const std::vector<float> costs{1.0f, 1.5f, 8.0f};  // stairs at 1, 1.5 and 8 times a level metre
  queue.setStairCosts(costs);
  EXPECT_EQ(queue.costClasses(), 3u);
  std::vector<PathTicket> tickets;
  for (std::uint32_t c = 0; c < 4; ++c) tickets.push_back(queue.request({5, 1}, 0.0f, {26, 1}, 2.0f, c));
  while (queue.pending() > 0) queue.update(1000);
  const auto usesRamp = [&](PathTicket t) {
    const PathResult r = queue.take(t);
    EXPECT_EQ(r.status, PathStatus::Complete);
    return std::any_of(r.corners.begin(), r.corners.end(), [](Vec2 c) { return c.y > 3.0f; });
  };
  EXPECT_FALSE(usesRamp(tickets[0]));  // the stairs: 8 m shorter
  EXPECT_FALSE(usesRamp(tickets[1]));  // still: 0.5 × 3.9 m of stairs < 8 m
  EXPECT_TRUE(usesRamp(tickets[2]));   // 7 × 3.9 m > 8 m: the ramp
  EXPECT_FALSE(usesRamp(tickets[3]));  // no such class: the first one's costs
}

TEST(Terrain, UpperFloorWithoutRampIsUnreachable) {
  auto mesh = buildTerrainOrFail(twoFloors(false));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  ASSERT_TRUE(query.snap({2, 5}, 0.0f));
  ASSERT_TRUE(query.snap({2, 5}, 3.0f));
  EXPECT_FALSE(query.reachable({2, 5}, 0.0f, {2, 5}, 3.0f));
  std::vector<Vec2> corners;
  EXPECT_EQ(query.findPath({2, 5}, 0.0f, {18, 5}, 3.0f, corners), PathStatus::Partial);
  EXPECT_TRUE(query.reachable({2, 5}, 0.0f, {18, 5}, 0.0f));
}

TEST(Terrain, ObstacleBoxRemovesWalkableArea) {
  TerrainMesh terrain = twoFloors(true);
  TerrainWriter w;
  w.mesh = terrain;
  w.box(8, 2, 0, 10, 4, 1);  // on the ground floor, 1 m high (its top is not walkable either)
  auto mesh = buildTerrainOrFail(w.mesh);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  EXPECT_FALSE(query.snap({9, 3}, 0.0f, 0.3f));
  EXPECT_FALSE(query.snap({9, 3}, 1.0f, 0.3f));  // the box top
  const auto pushed = query.snap({9, 3}, 0.0f, 2.0f);
  ASSERT_TRUE(pushed);
  EXPECT_NEAR(pushed->height, 0.0f, kHeightTolerance);
  const bool outside = pushed->p.x <= 8.0f - 0.1f || pushed->p.x >= 10.0f + 0.1f || pushed->p.y <= 2.0f - 0.1f ||
                       pushed->p.y >= 4.0f + 0.1f;
  EXPECT_TRUE(outside) << pushed->p.x << ", " << pushed->p.y;
  // The upper floor above the box is untouched; the ground floor path goes around it.
  const auto above = query.snap({9, 3}, 3.0f, 0.3f);
  ASSERT_TRUE(above);
  EXPECT_NEAR(above->height, 3.0f, kHeightTolerance);
  EXPECT_FALSE(query.visible({6, 3}, 0.0f, {12, 3}));
  EXPECT_TRUE(query.visible({6, 3}, 3.0f, {12, 3}));
  std::vector<Vec2> corners;
  ASSERT_EQ(query.findPath({6, 3}, 0.0f, {12, 3}, 0.0f, corners), PathStatus::Complete);
  EXPECT_GT(corners.size(), 1u);
}

TEST(Terrain, RandomMeshPointsLieOnBothLevels) {
  auto mesh = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  int ground = 0, upper = 0;
  for (int i = 0; i < 200; ++i) {
    const float r0 = static_cast<float>(i) / 200.0f;
    const auto point = query.randomMeshPoint(r0, 0.37f, 0.61f);
    ASSERT_TRUE(point);
    const auto plain = query.randomPoint(r0, 0.37f, 0.61f);
    ASSERT_TRUE(plain);
    EXPECT_EQ(point->p.x, plain->x);
    EXPECT_EQ(point->p.y, plain->y);
    EXPECT_NE(point->ref, 0u);
    EXPECT_GE(point->height, mesh->minHeight() - kHeightTolerance);
    EXPECT_LE(point->height, mesh->maxHeight() + kHeightTolerance);
    EXPECT_NEAR(query.heightAt(point->ref, point->p), point->height, 1e-3f);
    if (point->p.y < 9.5f) {  // on a floor
      if (std::abs(point->height) < kHeightTolerance) ++ground;
      else if (std::abs(point->height - 3.0f) < kHeightTolerance) ++upper;
      else ADD_FAILURE() << "height " << point->height << " on a floor";
    }
  }
  EXPECT_GT(ground, 40);
  EXPECT_GT(upper, 40);
}

TEST(Terrain, MoveAlongSurfaceStaysOnItsLevel) {
  auto mesh = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  auto upper = query.snap({5, 5}, 3.0f);
  ASSERT_TRUE(upper);
  PolyRef ref = upper->ref;
  Vec2 p = upper->p;
  for (int i = 0; i < 20; ++i) p = query.moveAlongSurface(p, p + Vec2{0.5f, 0.0f}, ref);
  EXPECT_NEAR(p.x, 15.0f, 0.01f);
  EXPECT_NEAR(query.heightAt(ref, p), 3.0f, kHeightTolerance);  // still upstairs
}

TEST(Terrain, BuildIsDeterministic) {
  auto a = buildTerrainOrFail(twoFloors(true));
  auto b = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->polygonCount(), b->polygonCount());
  NavQuery qa(a), qb(b);
  for (float x = 1.0f; x < 20.0f; x += 3.0f) {
    for (const float h : {0.0f, 3.0f}) {
      const auto sa = qa.snap({x, 5}, h);
      const auto sb = qb.snap({x, 5}, h);
      ASSERT_TRUE(sa && sb);
      EXPECT_EQ(sa->ref, sb->ref);
      EXPECT_EQ(sa->height, sb->height);
    }
  }
}

TEST(Terrain, BadInputIsDiagnosed) {
  TerrainMesh outOfRange = twoFloors(false);
  outOfRange.walkable[3] = 999;
  auto r1 = NavMesh::buildFromTerrain(outOfRange, {});
  ASSERT_FALSE(r1.ok());
  EXPECT_TRUE(hasPointer(r1.errors(), "/terrain/walkable/3")) << core::formatAll(r1.errors());

  TerrainMesh noWalkable = twoFloors(false);
  noWalkable.obstacles = noWalkable.walkable;
  noWalkable.walkable.clear();
  auto r2 = NavMesh::buildFromTerrain(noWalkable, {});
  ASSERT_FALSE(r2.ok());
  EXPECT_TRUE(hasPointer(r2.errors(), "/terrain/walkable")) << core::formatAll(r2.errors());

  TerrainMesh nonFinite = twoFloors(false);
  nonFinite.vertices[4] = std::numeric_limits<float>::quiet_NaN();
  nonFinite.obstacles = {0, 1};  // not a multiple of 3
  auto r3 = NavMesh::buildFromTerrain(nonFinite, {});
  ASSERT_FALSE(r3.ok());
  EXPECT_TRUE(hasPointer(r3.errors(), "/terrain/vertices/4")) << core::formatAll(r3.errors());
  EXPECT_TRUE(hasPointer(r3.errors(), "/terrain/obstacles")) << core::formatAll(r3.errors());

  // Only a wall: nothing walkable remains.
  TerrainWriter wall;
  wall.quad(wall.mesh.walkable, wall.vertex(0, 0, 0), wall.vertex(5, 0, 0), wall.vertex(5, 0, 3),
            wall.vertex(0, 0, 3));
  auto r4 = NavMesh::buildFromTerrain(wall.mesh, {});
  ASSERT_FALSE(r4.ok());
  EXPECT_TRUE(hasPointer(r4.errors(), "/terrain/walkable")) << core::formatAll(r4.errors());

  NavMeshConfig badConfig;
  badConfig.maxSlopeDeg = 95.0f;
  badConfig.clearance = -1.0f;
  auto r5 = NavMesh::buildFromTerrain(twoFloors(true), badConfig);
  ASSERT_FALSE(r5.ok());
  EXPECT_TRUE(hasPointer(r5.errors(), "/maxSlopeDeg"));
  EXPECT_TRUE(hasPointer(r5.errors(), "/clearance"));
}

TEST(Terrain, HeightOverloadsOnAFlatMeshMatchThePlainQueries) {
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, testing::doorWall(1.2f));
  ASSERT_TRUE(mesh);
  EXPECT_FALSE(mesh->layered());
  EXPECT_EQ(mesh->minHeight(), 0.0f);
  EXPECT_EQ(mesh->maxHeight(), 0.0f);
  NavQuery query(mesh);
  PathQueue queue(mesh);
  for (const Vec2 p : {Vec2{2, 2}, Vec2{10, 5}, Vec2{-1, 5}, Vec2{19.95f, 9.95f}, Vec2{10, 1}}) {
    const auto plain = query.nearest(p, 1.5f);
    const auto snapped = query.snap(p, 7.0f, 1.5f);  // the height is ignored
    ASSERT_EQ(plain.has_value(), snapped.has_value());
    if (plain) {
      EXPECT_EQ(snapped->p.x, plain->first.x);
      EXPECT_EQ(snapped->p.y, plain->first.y);
      EXPECT_EQ(snapped->ref, plain->second);
      EXPECT_EQ(snapped->height, 0.0f);
      EXPECT_EQ(query.heightAt(snapped->ref, p), 0.0f);
    }
    const Vec2 to{17, 8};
    std::vector<Vec2> a, b;
    EXPECT_EQ(query.findPath(p, to, a), query.findPath(p, 4.0f, to, -3.0f, b));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].x, b[i].x);
      EXPECT_EQ(a[i].y, b[i].y);
    }
    EXPECT_EQ(query.reachable(p, to), query.reachable(p, 2.0f, to, 9.0f));
    EXPECT_EQ(query.visible(p, to), query.visible(p, 5.0f, to));
    const PathTicket t1 = queue.request(p, to);
    const PathTicket t2 = queue.request(p, 3.0f, to, 3.0f);
    while (queue.pending() > 0) queue.update(100);
    const PathResult q1 = queue.take(t1);
    const PathResult q2 = queue.take(t2);
    EXPECT_EQ(q1.status, q2.status);
    ASSERT_EQ(q1.corners.size(), q2.corners.size());
    for (std::size_t i = 0; i < q1.corners.size(); ++i) {
      EXPECT_EQ(q1.corners[i].x, q2.corners[i].x);
      EXPECT_EQ(q1.corners[i].y, q2.corners[i].y);
    }
  }
  for (int i = 0; i < 50; ++i) {
    const float r = static_cast<float>(i) / 50.0f;
    const auto plain = query.randomPoint(r, 1.0f - r, 0.5f * r);
    const auto meshPoint = query.randomMeshPoint(r, 1.0f - r, 0.5f * r);
    ASSERT_TRUE(plain && meshPoint);
    EXPECT_EQ(meshPoint->p.x, plain->x);
    EXPECT_EQ(meshPoint->p.y, plain->y);
    EXPECT_EQ(meshPoint->height, 0.0f);
    EXPECT_NE(meshPoint->ref, 0u);
  }
}

// nav::DistanceField on layered meshes (distance_field.cpp): floors above each other keep their
// own distances, and stairs cost their factor.
TEST(Terrain, DistanceFieldsKeepFloorsApartAndPriceStairs) {
  auto two = buildTerrainOrFail(twoFloors(true));
  ASSERT_TRUE(two);
  NavQuery q2(two);
  // The target on the upper floor's east end: from the ground floor the way runs along the ramp.
  const DistanceField up = DistanceField::build(*two, FieldTarget{{19, 5}, 0.5f, {}, 3.0f});
  const auto ground = q2.snap({10, 5}, 0.0f), upper = q2.snap({10, 5}, 3.0f);
  ASSERT_TRUE(ground && upper);
  const float dUpper = up.at(upper->p, upper->ref), dGround = up.at(ground->p, ground->ref);
  EXPECT_NEAR(dUpper, 8.5f, 0.3f);                // straight along the upper floor
  EXPECT_GT(dGround, dUpper + 10.0f);             // down there: to the ramp, up it, back east
  EXPECT_LT(dGround, 40.0f);

  auto mesh = buildTerrainOrFail(stairOrRamp());
  ASSERT_TRUE(mesh);
  NavQuery q(mesh);
  const auto start = q.snap({5, 1}, 0.0f);
  ASSERT_TRUE(start);
  const FieldTarget end{{26, 1}, 0.5f, {}, 2.0f};
  DistanceFieldConfig cheap, dear;
  dear.stairCost = 8.0f;
  const float viaStairs = DistanceField::build(*mesh, end, cheap).at(start->p, start->ref);
  const float viaRamp = DistanceField::build(*mesh, end, dear).at(start->p, start->ref);
  EXPECT_NEAR(viaStairs, 20.5f, 1.0f);  // 21 m east, stairs counted at their plan length
  EXPECT_GT(viaRamp, viaStairs + 2.0f);  // eight-fold stairs: the ramp's detour is cheaper
  EXPECT_LT(viaRamp, viaStairs + 7.0f * 2.4f);
}

}  // namespace
}  // namespace throng::nav

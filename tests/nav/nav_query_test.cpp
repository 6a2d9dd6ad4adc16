// Tests for throng::nav::NavQuery (libs/nav/src/nav_query.cpp): paths around obstacles,
// moveAlongSurface never leaving the mesh, visibility, deterministic area-weighted random points.
#include <gtest/gtest.h>

#include "nav_test_worlds.hpp"
#include "throng/core/rng.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {
namespace {
using testing::buildOrFail;
using testing::insideRect;
using testing::rect;

TEST(NavQuery, PathGoesAroundAWallBlock) {
  // The block touches neither edge: 20 x 20 room, block x 8..12, y 2..18.
  auto mesh = buildOrFail({rect(0, 0, 20, 20)}, {rect(8, 2, 12, 18)});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  const Vec2 from{4, 10};
  const Vec2 to{16, 10};
  std::vector<Vec2> corners;
  ASSERT_EQ(query.findPath(from, to, corners), PathStatus::Complete);
  ASSERT_GE(corners.size(), 3u);  // two turns around the block, then the target
  EXPECT_NEAR(corners.back().x, to.x, 1e-3f);
  EXPECT_GT(testing::pathLength(from, corners), distance(from, to) + 4.0f);
  Vec2 prev = from;
  for (Vec2 c : corners) {
    for (int k = 0; k <= 100; ++k) {
      const Vec2 p = prev + (c - prev) * (static_cast<float>(k) / 100.0f);
      EXPECT_FALSE(insideRect(p, 8, 2, 12, 18)) << p.x << "," << p.y;
    }
    prev = c;
  }
  EXPECT_FALSE(query.visible(from, to));
  EXPECT_TRUE(query.visible({4, 10}, {4, 19}));
}

TEST(NavQuery, StartOffMeshFailsAndTargetOffMeshIsPartial) {
  auto mesh = buildOrFail({rect(0, 0, 10, 10)}, {});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  std::vector<Vec2> corners;
  EXPECT_EQ(query.findPath({50, 50}, {5, 5}, corners), PathStatus::Failed);
  EXPECT_TRUE(corners.empty());
  EXPECT_EQ(query.findPath({5, 5}, {50, 50}, corners), PathStatus::Partial);
  EXPECT_FALSE(query.nearest({50, 50}));
  auto hit = query.nearest({5, 5});
  ASSERT_TRUE(hit);
  EXPECT_NE(hit->second, 0u);
  EXPECT_NEAR(hit->first.x, 5.0f, 1e-4f);
}

TEST(NavQuery, MoveAlongSurfaceNeverLeavesTheMesh) {
  const std::vector<Polygon> obstacles = {rect(3, 3, 5, 7), rect(8, 1, 9, 9), rect(12, 4, 16, 5)};
  auto mesh = buildOrFail({rect(0, 0, 20, 10)}, obstacles);
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  const float radius = mesh->config().agentRadius;
  const float slack = mesh->config().cellSize * 1.5f;
  core::Rng rng(42, 0, core::RngPurpose::Bench);
  Vec2 pos{1, 1};
  PolyRef ref = 0;
  for (int step = 0; step < 2000; ++step) {
    const float angle = static_cast<float>(rng.uniform(0.0, 6.283185307179586));
    const float len = static_cast<float>(rng.uniform(0.0, 3.0));
    const Vec2 target = pos + Vec2{std::cos(angle), std::sin(angle)} * len;
    pos = query.moveAlongSurface(pos, target, ref);
    ASSERT_NE(ref, 0u);
    auto on = query.nearest(pos, 0.5f);
    ASSERT_TRUE(on);
    ASSERT_LT(distance(on->first, pos), 1e-3f) << "step " << step;
    ASSERT_GE(pos.x, radius - slack);
    ASSERT_LE(pos.x, 20.0f - radius + slack);
    ASSERT_GE(pos.y, radius - slack);
    ASSERT_LE(pos.y, 10.0f - radius + slack);
    for (const Polygon& o : obstacles) ASSERT_FALSE(insideRect(pos, o[0].x, o[0].y, o[2].x, o[2].y)) << "step " << step;
    if (step % 97 == 0) ref = 0;  // an invalid ref re-snaps
  }
}

TEST(NavQuery, RandomPointIsOnTheMeshDeterministicAndAreaWeighted) {
  // Two rooms joined by a corridor; the right room has three times the area of the left.
  const std::vector<Polygon> walkable = {rect(0, 0, 10, 10), rect(10, 4, 20, 6), rect(20, 0, 50, 10)};
  auto mesh = buildOrFail(walkable, {});
  ASSERT_TRUE(mesh);
  NavQuery query(mesh);
  NavQuery other(mesh);
  core::Rng rng(7, 0, core::RngPurpose::Spawn);
  int left = 0;
  int right = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const auto r0 = static_cast<float>(rng.uniform());
    const auto r1 = static_cast<float>(rng.uniform());
    const auto r2 = static_cast<float>(rng.uniform());
    auto p = query.randomPoint(r0, r1, r2);
    ASSERT_TRUE(p);
    auto q = other.randomPoint(r0, r1, r2);
    ASSERT_TRUE(q);
    EXPECT_EQ(p->x, q->x);
    EXPECT_EQ(p->y, q->y);
    auto on = query.nearest(*p, 0.1f);
    ASSERT_TRUE(on);
    EXPECT_LT(distance(on->first, *p), 1e-3f);
    left += p->x < 10.0f;
    right += p->x > 20.0f;
  }
  EXPECT_NEAR(static_cast<double>(right) / left, 3.0, 0.4);
  // Edge values are clamped, never out of range.
  EXPECT_TRUE(query.randomPoint(0.0f, 0.0f, 0.0f));
  EXPECT_TRUE(query.randomPoint(1.0f, 1.0f, 1.0f));
}

}  // namespace
}  // namespace throng::nav

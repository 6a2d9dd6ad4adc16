// Tests for throng::nav::DistanceField (libs/nav/src/distance_field.cpp): distances agree with the
// straight line in open space and with Detour's paths round walls, across tiles; unreachable
// places and targets off the mesh answer kUnreachable; stairs cost more.
#include "throng/nav/distance_field.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "nav_test_worlds.hpp"

namespace throng::nav {
namespace {

using testing::buildOrFail;
using testing::rect;

float fieldAt(const DistanceField& f, const NavQuery& q, Vec2 p) {
  const auto hit = q.nearest(p, 0.5f);
  if (!hit) return -1.0f;
  return f.at(hit->first, hit->second);
}

TEST(DistanceField, OpenSpaceIsTheStraightLine) {
  const auto mesh = buildOrFail({rect(0, 0, 30, 10)}, {});
  ASSERT_TRUE(mesh);
  const DistanceField f = DistanceField::build(*mesh, FieldTarget{{29.0f, 5.0f}, 0.5f, {}, 0.0f});
  ASSERT_FALSE(f.empty());
  NavQuery q(mesh);
  for (const Vec2 p : {Vec2{1, 1}, Vec2{5, 9}, Vec2{15, 5}, Vec2{28, 2}, Vec2{29, 5}}) {
    const float straight = std::max(0.0f, core::length(p - Vec2{29, 5}) - 0.5f);
    EXPECT_NEAR(fieldAt(f, q, p), straight, 0.02f * straight + 0.05f) << p.x << "," << p.y;
  }
}

TEST(DistanceField, GoesRoundWallsLikeAPath) {
  // The 20 x 10 m room split by a wall with a 1 m door; the target lies beyond the wall.
  const auto mesh = buildOrFail({rect(0, 0, 20, 10)}, testing::doorWall(1.0f));
  ASSERT_TRUE(mesh);
  const Vec2 goal{18.0f, 2.0f};
  const DistanceField f = DistanceField::build(*mesh, FieldTarget{goal, 0.0f, {}, 0.0f});
  NavQuery q(mesh);
  for (const Vec2 p : {Vec2{2, 1}, Vec2{2, 9}, Vec2{9, 0.5f}, Vec2{9.5f, 9.5f}, Vec2{5, 5}, Vec2{12, 8}}) {
    std::vector<Vec2> corners;
    ASSERT_EQ(q.findPath(p, goal, corners), PathStatus::Complete);
    const float path = testing::pathLength(p, corners);
    EXPECT_NEAR(fieldAt(f, q, p), path, 0.03f * path + 0.1f) << p.x << "," << p.y;
  }
  // Next to the wall, north of the door, the wall makes a detour of about a metre.
  EXPECT_GT(fieldAt(f, q, {9.5f, 9.5f}), core::length(Vec2{9.5f, 9.5f} - goal) + 0.8f);
}

TEST(DistanceField, CrossesTilesAndPillarFields) {
  // 60 m: three 24 m tiles; pillars every 6 m.
  const auto mesh = buildOrFail({rect(0, 0, 60, 30)}, testing::pillars(30.0f, 6.0f));
  ASSERT_TRUE(mesh);
  const Vec2 goal{58.0f, 15.0f};
  const DistanceField f = DistanceField::build(*mesh, FieldTarget{goal, 1.0f, {}, 0.0f});
  NavQuery q(mesh);
  for (const Vec2 p : {Vec2{1, 1}, Vec2{2, 28}, Vec2{20, 14}, Vec2{40, 3}}) {
    std::vector<Vec2> corners;
    ASSERT_EQ(q.findPath(p, goal, corners), PathStatus::Complete);
    const float path = testing::pathLength(p, corners) - 1.0f;  // to the disc's edge
    // Detour's string-pulled path is not always the shortest: allow it to be a little longer.
    EXPECT_NEAR(fieldAt(f, q, p), path, 0.04f * path + 0.2f) << p.x << "," << p.y;
  }
}

TEST(DistanceField, UnreachablePlacesAndTargetsOffTheMesh) {
  const auto mesh = buildOrFail({rect(0, 0, 10, 10), rect(20, 0, 30, 10)}, {});
  ASSERT_TRUE(mesh);
  NavQuery q(mesh);
  const DistanceField f = DistanceField::build(*mesh, FieldTarget{{5, 5}, 0.5f, {}, 0.0f});
  EXPECT_LT(fieldAt(f, q, {1, 1}), 10.0f);
  EXPECT_EQ(fieldAt(f, q, {25, 5}), DistanceField::kUnreachable);
  EXPECT_EQ(f.at({5, 5}, 0), DistanceField::kUnreachable);  // no polygon
  // A polygon target just beyond the eroded edge is reached from the polygons next to it ...
  const DistanceField edge = DistanceField::build(*mesh, FieldTarget{{}, 0.0f, rect(10.0f, 4.0f, 11.0f, 6.0f), 0.0f});
  EXPECT_NEAR(fieldAt(edge, q, {5, 5}), 5.0f, 0.4f);
  // ... one far away is not.
  const DistanceField far = DistanceField::build(*mesh, FieldTarget{{50, 50}, 1.0f, {}, 0.0f});
  EXPECT_TRUE(far.empty());
  EXPECT_EQ(fieldAt(far, q, {5, 5}), DistanceField::kUnreachable);
}

TEST(DistanceField, IsTheSameOnEveryBuild) {
  const auto mesh = buildOrFail({rect(0, 0, 60, 30)}, testing::pillars(30.0f, 6.0f));
  ASSERT_TRUE(mesh);
  const DistanceField a = DistanceField::build(*mesh, FieldTarget{{58, 15}, 1.0f, {}, 0.0f});
  const DistanceField b = DistanceField::build(*mesh, FieldTarget{{58, 15}, 1.0f, {}, 0.0f});
  NavQuery q(mesh);
  for (float x = 1; x < 60; x += 7.3f)
    for (float y = 1; y < 30; y += 4.1f) {
      const float da = fieldAt(a, q, {x, y}), db = fieldAt(b, q, {x, y});
      EXPECT_EQ(da, db);
    }
}

}  // namespace
}  // namespace throng::nav

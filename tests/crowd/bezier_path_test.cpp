// Tests for libs/crowd/src/bezier_path.cpp: the min-max box check and buildPath (§3.2.2), on
// polygons, on region corridors and on a navigation mesh.
#include "throng/crowd/bezier_path.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "crowd_test_util.hpp"
#include "throng/core/diagnostic.hpp"
#include "throng/nav/navmesh.hpp"

namespace crowd = throng::crowd;
namespace core = throng::core;
namespace nav = throng::nav;
using core::Vec2;
using crowd::testing::rect;

namespace {

/// Dense sampling of the curve: every point must satisfy `inside`.
template <class F>
bool denselyInside(const crowd::BezierCurve& c, F inside, int samples = 400) {
  for (int i = 0; i <= samples; ++i) {
    if (!inside(crowd::evaluate(c.points, float(i) / float(samples)))) return false;
  }
  return true;
}

/// The oracle for "a path must exist": the straight line from `a` to `b`, sampled every 2 cm, stays
/// inside the layout and at least `margin` from every wall and obstacle edge. buildPath's last
/// resort is that straight line at the walkable clearance (0.2 m below), so with a larger margin it
/// must never give up. Independent of buildPath's exact segment test.
bool clearlyVisible(const crowd::testing::Layout& l, Vec2 a, Vec2 b, float margin) {
  const int samples = std::max(2, static_cast<int>(core::distance(a, b) / 0.02f));
  for (int i = 0; i <= samples; ++i) {
    const Vec2 p = a + (b - a) * (float(i) / float(samples));
    if (!crowd::testing::insideLayout(l, p)) return false;
    if (core::distanceToBoundary(l.walkable, p) < margin) return false;
    for (const auto& o : l.obstacles) {
      if (core::distanceToBoundary(o, p) < margin) return false;
    }
  }
  return true;
}

}  // namespace

TEST(VerifyCurve, AcceptsFreeCurvesAndRejectsBlockedOnes) {
  const crowd::PolygonWalkable w({rect(0, 0, 20, 10)}, {rect(9, 4, 11, 6)});
  int tests = 0;
  // A C-shaped cubic passing below the obstacle.
  EXPECT_TRUE(crowd::verifyCurve(crowd::makeBentCubic({2, 5}, {18, 5}, -0.3f, -0.3f).points, w, 6, &tests));
  EXPECT_GT(tests, 1) << "the whole box contains the obstacle: must have subdivided";
  // Straight through the obstacle: rejected whatever the depth.
  EXPECT_FALSE(crowd::verifyCurve(crowd::makeBentCubic({2, 5}, {18, 5}, 0.0f, 0.0f).points, w, 10));
  // A cubic leaving the room.
  EXPECT_FALSE(crowd::verifyCurve(crowd::makeBentCubic({2, 5}, {18, 5}, 0.6f, 0.6f).points, w, 8));
  // Degree 1 is checked exactly: a diagonal segment whose box would contain the obstacle.
  int segTests = 0;
  EXPECT_TRUE(crowd::verifyCurve(std::vector<Vec2>{{1, 1}, {19, 3.5f}}, w, 0, &segTests));
  EXPECT_EQ(segTests, 1);
}

TEST(VerifyCurve, DepthZeroIsTheSingleControlBox) {
  const crowd::PolygonWalkable w({rect(0, 0, 20, 10)}, {rect(9, 4, 11, 6)});
  const auto c = crowd::makeBentCubic({2, 5}, {18, 5}, -0.3f, -0.3f);
  EXPECT_FALSE(crowd::verifyCurve(c.points, w, 0));
}

TEST(BuildPath, ReturnsAVerifiedCurveFromStartToTarget) {
  const crowd::PolygonWalkable w({rect(0, 0, 20, 10)}, {rect(9, 4, 11, 6)}, 0.2f);
  core::Rng rng(1, 2, core::RngPurpose::Behaviour);
  const auto c = crowd::buildPath({2, 5}, {18, 5}, w, {}, rng);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->start(), Vec2(2, 5));
  EXPECT_EQ(c->end(), Vec2(18, 5));
  EXPECT_EQ(c->degree(), 3u);
  EXPECT_TRUE(denselyInside(*c, [&](Vec2 p) { return w.pointInside(p); }));
}

TEST(BuildPath, FallsBackToTheStraightLineThenGivesUp) {
  // A 0.8 m wide corridor: bends fail, the straight line fits.
  const crowd::PolygonWalkable corridor({rect(0, 0, 30, 0.8f)}, {});
  core::Rng rng(3, 4, core::RngPurpose::Behaviour);
  crowd::BezierPathParams p;
  p.maxBend = 0.3f;
  p.attempts = 2;
  const auto c = crowd::buildPath({1, 0.4f}, {29, 0.4f}, corridor, p, rng);
  ASSERT_TRUE(c.has_value());
  EXPECT_LE(c->degree(), 3u);
  EXPECT_TRUE(denselyInside(*c, [&](Vec2 q) { return corridor.pointInside(q); }));
  p.attempts = 0;
  const auto straight = crowd::buildPath({1, 0.4f}, {29, 0.4f}, corridor, p, rng);
  ASSERT_TRUE(straight.has_value());
  EXPECT_EQ(straight->degree(), 1u);

  // Target behind a wall with a door elsewhere: no curve of this family reaches it.
  const crowd::PolygonWalkable rooms({rect(0, 0, 20, 10)}, {rect(9.9f, 0, 10.1f, 8), rect(9.9f, 9, 10.1f, 10)});
  EXPECT_FALSE(crowd::buildPath({5, 2}, {15, 2}, rooms, {}, rng).has_value());
  // Start or target off the walkable area.
  EXPECT_FALSE(crowd::buildPath({-5, 2}, {5, 2}, rooms, {}, rng).has_value());
}

TEST(BuildPath, DeterministicPerStream) {
  const crowd::PolygonWalkable w({rect(0, 0, 40, 40)}, {});
  core::Rng a(9, 17, core::RngPurpose::Behaviour);
  core::Rng b(9, 17, core::RngPurpose::Behaviour);
  core::Rng other(9, 18, core::RngPurpose::Behaviour);
  const auto ca = crowd::buildPath({5, 5}, {35, 30}, w, {}, a);
  const auto cb = crowd::buildPath({5, 5}, {35, 30}, w, {}, b);
  const auto co = crowd::buildPath({5, 5}, {35, 30}, w, {}, other);
  ASSERT_TRUE(ca && cb && co);
  EXPECT_EQ(ca->points, cb->points);
  EXPECT_NE(ca->points, co->points);
  // Exactly two draws per call, whatever the outcome.
  core::Rng c(9, 17, core::RngPurpose::Behaviour);
  (void)crowd::buildPath({-50, 5}, {35, 30}, w, {}, c);  // start off the area: nullopt
  EXPECT_EQ(a.next(), c.next());
}

// "Every Bézier path lies inside the walkable area and its regions": random rooms and L-shapes
// with random obstacles, random start and target; whatever buildPath returns is walkable at 400
// points along it, starts at the start and ends at the target.
RC_GTEST_PROP(BuildPath, EveryCurveLiesInsideTheWalkableArea, (std::uint64_t seed)) {
  const auto layout = crowd::testing::randomLayout(seed);
  const crowd::PolygonWalkable w({layout.walkable}, layout.obstacles, 0.2f);
  core::Rng rng(seed, 7, core::RngPurpose::Behaviour);
  int built = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 from = crowd::testing::randomWalkablePoint(layout, w, rng);
    const Vec2 to = crowd::testing::randomWalkablePoint(layout, w, rng);
    const auto c = crowd::buildPath(from, to, w, {}, rng);
    if (!c) {
      // Giving up is right only where no straight line is free: never count a failure as a pass.
      RC_ASSERT(!clearlyVisible(layout, from, to, 0.25f));
      RC_TAG("no curve: the straight line is blocked");
      continue;
    }
    ++built;
    RC_CLASSIFY(c->degree() == 3, "bent cubic");
    RC_CLASSIFY(c->degree() == 1, "straight line");
    RC_ASSERT(c->start() == from);
    RC_ASSERT(c->end() == to);
    RC_ASSERT(denselyInside(*c, [&](Vec2 p) { return crowd::testing::insideLayout(layout, p); }));
  }
  RC_CLASSIFY(built > 0, "some curve built");
}

RC_GTEST_PROP(BuildPath, EveryCurveLiesInsideItsRegionCorridor, (std::uint64_t seed)) {
  const auto layout = crowd::testing::randomLayout(seed);
  const crowd::PolygonWalkable w({layout.walkable}, layout.obstacles, 0.2f);
  core::Rng rng(seed, 8, core::RngPurpose::Behaviour);
  // A corridor of three overlapping discs from a walkable point towards another.
  const Vec2 from = crowd::testing::randomWalkablePoint(layout, w, rng);
  const Vec2 to = crowd::testing::randomWalkablePoint(layout, w, rng);
  const float r = std::max(1.5f, 0.3f * core::distance(from, to));
  const std::vector<crowd::Region> corridor{crowd::Region::disc(from, r),
                                            crowd::Region::disc((from + to) * 0.5f, r),
                                            crowd::Region::disc(to, r)};
  const auto c = crowd::buildPath(from, to, corridor, w, {}, rng);
  if (!c) {
    // The discs are centred on the straight line, so the line lies in the corridor: giving up is
    // right only where the walls block it.
    RC_ASSERT(!clearlyVisible(layout, from, to, 0.25f));
    return;
  }
  RC_ASSERT(denselyInside(*c, [&](Vec2 p) {
    bool inRegion = false;
    for (const auto& reg : corridor) inRegion = inRegion || crowd::regionContains(reg, p);
    return inRegion && crowd::testing::insideLayout(layout, p);
  }));
}

TEST(BuildPath, OnANavigationMeshStaysOnTheMesh) {
  std::vector<core::Polygon> pillars;
  for (float x = 4; x < 30; x += 6)
    for (float y = 4; y < 20; y += 6) pillars.push_back(rect(x - 0.5f, y - 0.5f, x + 0.5f, y + 0.5f));
  nav::NavMeshConfig cfg;
  cfg.agentRadius = 0.2f;
  auto built = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 32, 22)}, pillars, cfg);
  ASSERT_TRUE(built.ok()) << core::formatAll(built.errors());
  const nav::NavQuery q(built.value());
  const crowd::NavMeshWalkable w(q, 0.4f);
  const crowd::PolygonWalkable eroded({rect(0.1f, 0.1f, 31.9f, 21.9f)}, [&] {
    std::vector<core::Polygon> grown;
    for (const auto& p : pillars) {
      const auto b = core::bounds(p);
      grown.push_back(rect(b.min.x - 0.1f, b.min.y - 0.1f, b.max.x + 0.1f, b.max.y + 0.1f));
    }
    return grown;
  }());
  core::Rng rng(5, 1, core::RngPurpose::Behaviour);
  int built_ = 0;
  for (int k = 0; k < 30; ++k) {
    const Vec2 from{float(rng.uniform(1, 31)), float(rng.uniform(1, 21))};
    const Vec2 to{float(rng.uniform(1, 31)), float(rng.uniform(1, 21))};
    const auto c = crowd::buildPath(from, to, w, {}, rng);
    if (!c) continue;
    ++built_;
    EXPECT_TRUE(denselyInside(*c, [&](Vec2 p) { return eroded.pointInside(p); }, 200));
  }
  EXPECT_GT(built_, 5);
}

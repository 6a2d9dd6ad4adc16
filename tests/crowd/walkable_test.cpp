// Tests for libs/crowd/src/walkable.cpp and region.cpp: polygon, navigation-mesh and corridor
// oracles of the min-max box check.
#include "throng/crowd/walkable.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "crowd_test_util.hpp"
#include "throng/core/diagnostic.hpp"
#include "throng/crowd/region.hpp"
#include "throng/nav/navmesh.hpp"

namespace crowd = throng::crowd;
namespace core = throng::core;
namespace nav = throng::nav;
using core::Aabb;
using core::Vec2;
using crowd::testing::rect;

TEST(PolygonWalkable, BoxesSegmentsPoints) {
  const crowd::PolygonWalkable w({rect(0, 0, 20, 10)}, {rect(9, 4, 11, 6)});
  EXPECT_TRUE(w.boxInside(Aabb{{1, 1}, {5, 5}}));
  EXPECT_FALSE(w.boxInside(Aabb{{18, 1}, {21, 5}}));    // crosses the outer wall
  EXPECT_FALSE(w.boxInside(Aabb{{8, 3}, {12, 7}}));     // obstacle strictly inside the box
  EXPECT_FALSE(w.boxInside(Aabb{{10, 5}, {10.5f, 5.5f}}));  // box inside the obstacle
  EXPECT_FALSE(w.boxInside(Aabb{{-5, -5}, {25, 15}}));  // box around everything
  EXPECT_TRUE(w.segmentInside({1, 1}, {19, 9}) == false);  // the diagonal crosses the obstacle
  EXPECT_TRUE(w.segmentInside({1, 1}, {19, 1}));
  EXPECT_TRUE(w.pointInside({1, 1}));
  EXPECT_FALSE(w.pointInside({10, 5}));
  EXPECT_FALSE(w.pointInside({-1, 5}));
}

TEST(PolygonWalkable, ClearanceShrinksTheArea) {
  const crowd::PolygonWalkable w({rect(0, 0, 20, 10)}, {rect(9, 4, 11, 6)}, 0.5f);
  EXPECT_FALSE(w.pointInside({0.3f, 5}));
  EXPECT_TRUE(w.pointInside({0.7f, 5}));
  EXPECT_FALSE(w.segmentInside({5, 6.3f}, {15, 6.3f}));  // passes 0.3 m from the obstacle
  EXPECT_TRUE(w.segmentInside({5, 6.7f}, {15, 6.7f}));
  EXPECT_FALSE(w.boxInside(Aabb{{1, 1}, {8.7f, 3.7f}}));   // grown box touches the obstacle's corner region
  EXPECT_TRUE(w.boxInside(Aabb{{1, 1}, {8.4f, 3.7f}}));
}

TEST(PolygonWalkable, LShapeNotchIsOutside) {
  const crowd::PolygonWalkable w({{{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}}}, {});
  EXPECT_TRUE(w.boxInside(Aabb{{1, 1}, {9, 3}}));
  EXPECT_FALSE(w.boxInside(Aabb{{1, 1}, {9, 9}}));  // covers the notch although every corner but one is walkable
  EXPECT_FALSE(w.segmentInside({9, 3}, {3, 9}));     // cuts the notch corner
  EXPECT_TRUE(w.segmentInside({9, 3}, {3, 3}));
}

// Oracle soundness: whatever box the polygon oracle accepts is walkable at every sampled point.
RC_GTEST_PROP(PolygonWalkable, AcceptedBoxesAreWalkableEverywhere, (std::uint64_t seed)) {
  const auto layout = crowd::testing::randomLayout(seed);
  const crowd::PolygonWalkable w({layout.walkable}, layout.obstacles);
  core::Rng rng(seed, 1, core::RngPurpose::Bench);
  const auto b = core::bounds(layout.walkable);
  for (int k = 0; k < 40; ++k) {
    const Vec2 c{float(rng.uniform(b.min.x, b.max.x)), float(rng.uniform(b.min.y, b.max.y))};
    const float hw = float(rng.uniform(0.0, 4.0)), hh = float(rng.uniform(0.0, 4.0));
    const Aabb box{{c.x - hw, c.y - hh}, {c.x + hw, c.y + hh}};
    if (!w.boxInside(box)) continue;
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const Vec2 p{box.min.x + (box.max.x - box.min.x) * i / 8.0f, box.min.y + (box.max.y - box.min.y) * j / 8.0f};
        RC_ASSERT(crowd::testing::insideLayout(layout, p));
      }
  }
}

TEST(Region, DiscAndPolygonContainment) {
  const auto disc = crowd::Region::disc({0, 0}, 2.0f);
  EXPECT_NEAR(crowd::regionArea(disc), 3.14159265 * 4.0, 1e-5);
  EXPECT_TRUE(crowd::regionContainsBox(disc, Aabb{{-1, -1}, {1, 1}}));
  EXPECT_FALSE(crowd::regionContainsBox(disc, Aabb{{-1.5f, -1.5f}, {1.5f, 1.5f}}));
  EXPECT_FLOAT_EQ(crowd::distanceToRegion(disc, {5, 0}), 3.0f);
  EXPECT_FLOAT_EQ(crowd::distanceToRegion(disc, {1, 0}), 0.0f);
  const auto poly = crowd::Region::poly(rect(0, 0, 4, 2));
  EXPECT_FLOAT_EQ(poly.centre.x, 2.0f);
  EXPECT_NEAR(crowd::regionArea(poly), 8.0, 1e-6);
  EXPECT_TRUE(crowd::regionContainsSegment(poly, {0.5f, 0.5f}, {3.5f, 1.5f}));
  EXPECT_FALSE(crowd::regionContainsSegment(poly, {0.5f, 0.5f}, {4.5f, 1.5f}));
  EXPECT_FLOAT_EQ(crowd::distanceToRegion(poly, {6, 1}), 2.0f);
}

TEST(RegionConstrainedWalkable, OnlyInsideTheCorridor) {
  const crowd::PolygonWalkable base({rect(0, 0, 20, 10)}, {});
  const std::vector<crowd::Region> corridor{crowd::Region::disc({3, 3}, 2.0f), crowd::Region::disc({6, 3}, 2.0f)};
  const crowd::RegionConstrainedWalkable w(base, corridor);
  EXPECT_TRUE(w.pointInside({3, 3}));
  EXPECT_FALSE(w.pointInside({10, 8}));  // walkable, but outside the corridor
  EXPECT_TRUE(w.boxInside(Aabb{{5, 2}, {7, 4}}));
  EXPECT_FALSE(w.boxInside(Aabb{{2, 2}, {7, 4}}));  // straddles two discs: the caller subdivides
  EXPECT_FALSE(w.segmentInside({3, 3}, {10, 8}));
  const crowd::RegionConstrainedWalkable open(base, {});
  EXPECT_TRUE(open.pointInside({10, 8}));
}

TEST(RegionConstrainedWalkable, ASegmentThroughOverlappingRegionsIsInsideTheCorridor) {
  // The straight line from (1, 3) to (9, 3) lies in the union of three overlapping regions, in none
  // alone: a path may run through a corridor of several (the straight-line fallback of buildPath
  // was refused there, a rare failure of BuildPath.EveryCurveLiesInsideItsRegionCorridor).
  const crowd::PolygonWalkable base({rect(0, 0, 20, 10)}, {});
  const std::vector<crowd::Region> corridor{crowd::Region::disc({1, 3}, 2.0f), crowd::Region::poly(rect(2.5f, 2, 6.5f, 4)),
                                            crowd::Region::disc({8.5f, 3}, 2.5f)};
  const crowd::RegionConstrainedWalkable w(base, corridor);
  EXPECT_TRUE(w.segmentInside({1, 3}, {9, 3}));
  EXPECT_TRUE(w.segmentInside({9, 3}, {1, 3}));
  EXPECT_FALSE(w.segmentInside({1, 3}, {8.5f, 5.2f}));  // leaves the rectangle through its top side, between the discs
  // A gap between the regions: not inside.
  const std::vector<crowd::Region> gap{crowd::Region::disc({1, 3}, 1.0f), crowd::Region::disc({4, 3}, 1.0f)};
  const crowd::RegionConstrainedWalkable gapped(base, gap);
  EXPECT_FALSE(gapped.segmentInside({1, 3}, {4, 3}));
  EXPECT_TRUE(gapped.segmentInside({0.5f, 3}, {1.5f, 3}));
}

namespace {

std::shared_ptr<const nav::NavMesh> buildMesh(const std::vector<core::Polygon>& walkable,
                                              const std::vector<core::Polygon>& obstacles) {
  nav::NavMeshConfig cfg;
  cfg.agentRadius = 0.2f;
  auto r = nav::NavMesh::build(walkable, obstacles, cfg);
  if (!r.ok()) {
    ADD_FAILURE() << core::formatAll(r.errors());
    return nullptr;
  }
  return r.value();
}

}  // namespace

TEST(NavMeshWalkable, ScanLinesFindHolesThatEdgesAndDiagonalsMiss) {
  // A 0.4 m pillar (0.8 m hole after 0.2 m erosion) away from the box's edges and diagonals.
  const auto mesh = buildMesh({rect(0, 0, 20, 10)}, {rect(9.8f, 2.3f, 10.2f, 2.7f)});
  ASSERT_TRUE(mesh);
  const nav::NavQuery q(mesh);
  const crowd::NavMeshWalkable w(q, 0.4f);
  const crowd::NavMeshWalkable coarse(q, 100.0f);
  const Aabb box{{1, 1}, {19, 9}};
  EXPECT_FALSE(w.boxInside(box));
  EXPECT_TRUE(coarse.boxInside(box)) << "edges and diagonals alone miss the hole";
  EXPECT_TRUE(w.boxInside(Aabb{{1, 4}, {19, 9}}));
  EXPECT_FALSE(w.boxInside(Aabb{{-1, 4}, {19, 9}}));  // off the mesh
  EXPECT_TRUE(w.pointInside({5, 5}));
  EXPECT_FALSE(w.pointInside({10, 2.5f}));
  EXPECT_FALSE(w.pointInside({0.05f, 5}));  // inside the room but within the eroded border
  EXPECT_TRUE(w.segmentInside({1, 5}, {19, 5}));
  EXPECT_FALSE(w.segmentInside({1, 2.5f}, {19, 2.5f}));
}

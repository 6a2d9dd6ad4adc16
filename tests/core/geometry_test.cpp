// Tests for libs/core/src/geometry.cpp: areas, containment, intersections, triangulation.
#include "throng/core/geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using throng::core::Polygon;
using throng::core::Vec2;
namespace core = throng::core;

namespace {
const Polygon kSquareCcw{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
const Polygon kSquareCw{{0, 0}, {0, 2}, {2, 2}, {2, 0}};
// An L shape (concave), CCW, area 3.
const Polygon kL{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}  // namespace

TEST(Geometry, SignedAreaFollowsWinding) {
  EXPECT_DOUBLE_EQ(core::signedArea(kSquareCcw), 4.0);
  EXPECT_DOUBLE_EQ(core::signedArea(kSquareCw), -4.0);
  EXPECT_DOUBLE_EQ(core::signedArea(kL), 3.0);
  EXPECT_DOUBLE_EQ(core::signedArea(Polygon{{0, 0}, {1, 1}}), 0.0);
  EXPECT_DOUBLE_EQ(core::signedArea(Polygon{{0, 0}, {1, 1}, {2, 2}}), 0.0);
}

TEST(Geometry, BoundsAndAabb) {
  const core::Aabb box = core::bounds(kL);
  EXPECT_TRUE(box.valid());
  EXPECT_EQ(box.min, Vec2(0, 0));
  EXPECT_EQ(box.max, Vec2(2, 2));
  EXPECT_TRUE(box.contains({1, 1}));
  EXPECT_TRUE(box.contains({2, 2}));
  EXPECT_FALSE(box.contains({2.1f, 1}));
  EXPECT_FALSE(core::Aabb{}.valid());
}

TEST(Geometry, PointInPolygonBothWindingsAndConcave) {
  EXPECT_TRUE(core::pointInPolygon(kSquareCcw, {1, 1}));
  EXPECT_TRUE(core::pointInPolygon(kSquareCw, {1, 1}));
  EXPECT_FALSE(core::pointInPolygon(kSquareCcw, {3, 1}));
  EXPECT_TRUE(core::pointInPolygon(kL, {0.5f, 1.5f}));
  EXPECT_FALSE(core::pointInPolygon(kL, {1.5f, 1.5f}));  // in the notch
}

TEST(Geometry, SegmentsIntersect) {
  EXPECT_TRUE(core::segmentsIntersect({0, 0}, {2, 2}, {0, 2}, {2, 0}));   // proper crossing
  EXPECT_TRUE(core::segmentsIntersect({0, 0}, {2, 0}, {1, 0}, {1, 1}));   // T touch
  EXPECT_TRUE(core::segmentsIntersect({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // collinear overlap
  EXPECT_FALSE(core::segmentsIntersect({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear apart
  EXPECT_FALSE(core::segmentsIntersect({0, 0}, {1, 0}, {0, 1}, {1, 1}));  // parallel
  EXPECT_FALSE(core::segmentsIntersect({0, 0}, {1, 1}, {2, 0}, {3, -5}));
}

TEST(Geometry, FindSelfIntersection) {
  EXPECT_FALSE(core::findSelfIntersection(kSquareCcw).has_value());
  EXPECT_FALSE(core::findSelfIntersection(kL).has_value());
  const Polygon bowtie{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  const auto hit = core::findSelfIntersection(bowtie);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->first, 0u);
  EXPECT_EQ(hit->second, 2u);
  // A vertex touching a non-adjacent edge.
  const Polygon touching{{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}};
  EXPECT_TRUE(core::findSelfIntersection(touching).has_value());
  // A spike folding back along its own edge.
  const Polygon spike{{0, 0}, {4, 0}, {2, 0}, {2, 3}};
  EXPECT_TRUE(core::findSelfIntersection(spike).has_value());
  // Collinear (flat) vertices are not an intersection.
  const Polygon flat{{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_FALSE(core::findSelfIntersection(flat).has_value());
}

TEST(Geometry, ClosestPointAndDistances) {
  EXPECT_EQ(core::closestPointOnSegment({1, 5}, {0, 0}, {2, 0}), Vec2(1, 0));
  EXPECT_EQ(core::closestPointOnSegment({-3, 1}, {0, 0}, {2, 0}), Vec2(0, 0));
  EXPECT_EQ(core::closestPointOnSegment({9, 1}, {0, 0}, {2, 0}), Vec2(2, 0));
  EXPECT_EQ(core::closestPointOnSegment({9, 1}, {1, 1}, {1, 1}), Vec2(1, 1));  // degenerate
  EXPECT_FLOAT_EQ(core::distanceToSegmentSq({1, 3}, {0, 0}, {2, 0}), 9.0f);
  EXPECT_FLOAT_EQ(core::distanceToBoundary(kSquareCcw, {1, 0.5f}), 0.5f);
  EXPECT_FLOAT_EQ(core::distanceToBoundary(kSquareCcw, {5, 2}), 3.0f);
}

TEST(Geometry, CentroidIsAreaWeighted) {
  const Vec2 c = core::centroid(kSquareCw);
  EXPECT_FLOAT_EQ(c.x, 1.0f);
  EXPECT_FLOAT_EQ(c.y, 1.0f);
  // L shape: 2x1 bar (centroid (1,0.5), area 2) + 1x1 block (centroid (0.5,1.5), area 1).
  const Vec2 l = core::centroid(kL);
  EXPECT_NEAR(l.x, (2 * 1.0 + 0.5) / 3.0, 1e-6);
  EXPECT_NEAR(l.y, (2 * 0.5 + 1.5) / 3.0, 1e-6);
  // Extra vertices on an edge do not move an area centroid (they would move a vertex average).
  const Polygon dense{{0, 0}, {0.5f, 0}, {1, 0}, {1.5f, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_NEAR(core::centroid(dense).x, 1.0, 1e-6);
}

namespace {
double triangulatedArea(const Polygon& poly, const std::vector<std::array<std::size_t, 3>>& tris) {
  double sum = 0;
  for (const auto& t : tris) {
    const Polygon tri{poly[t[0]], poly[t[1]], poly[t[2]]};
    const double a = core::signedArea(tri);
    EXPECT_GT(a, 0.0) << "triangles must be CCW";
    sum += a;
  }
  return sum;
}
}  // namespace

TEST(Geometry, TriangulateEitherWinding) {
  for (const Polygon& poly : {kSquareCcw, kSquareCw, kL}) {
    const auto tris = core::triangulate(poly);
    EXPECT_EQ(tris.size(), poly.size() - 2);
    EXPECT_NEAR(triangulatedArea(poly, tris), std::abs(core::signedArea(poly)), 1e-9);
  }
  // A comb: many reflex vertices.
  Polygon comb{{0, 0}, {10, 0}, {10, 3}};
  for (int i = 9; i >= 1; --i) {
    comb.push_back({float(i) + 0.5f, 1});
    comb.push_back({float(i), 3});
  }
  comb.push_back({0, 3});
  const auto tris = core::triangulate(comb);
  EXPECT_EQ(tris.size(), comb.size() - 2);
  EXPECT_NEAR(triangulatedArea(comb, tris), core::signedArea(comb), 1e-6);
  EXPECT_TRUE(core::triangulate(Polygon{{0, 0}, {1, 0}}).empty());
}

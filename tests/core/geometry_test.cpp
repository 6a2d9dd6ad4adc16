// Tests for libs/core/src/geometry.cpp: areas, containment, intersections, triangulation.
#include "throng/core/geometry.hpp"
#include "throng/core/polygon_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

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

namespace {

/// A regular n-gon of radius r (CCW).
Polygon circle(std::size_t n, float r) {
  Polygon p(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * double(i) / double(n);
    p[i] = Vec2(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)));
  }
  return p;
}

/// The reference: every pair of edges, first (i, j) in lexicographic order.
std::optional<std::pair<std::size_t, std::size_t>> allPairsReference(const Polygon& poly) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
      if (adjacent) {  // a spike: collinear, folding back from the shared vertex
        const Vec2 shared = j == i + 1 ? poly[j] : poly[0];
        const Vec2 p = j == i + 1 ? poly[i] : poly[1];
        const Vec2 q = j == i + 1 ? poly[(j + 1) % n] : poly[j];
        const double cross = (double(p.x) - shared.x) * (double(q.y) - shared.y) - (double(p.y) - shared.y) * (double(q.x) - shared.x);
        const double dot = (double(p.x) - shared.x) * (double(q.x) - shared.x) + (double(p.y) - shared.y) * (double(q.y) - shared.y);
        if (cross == 0.0 && dot > 0.0) return std::make_pair(i, j);
        continue;
      }
      if (core::segmentsIntersect(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) return std::make_pair(i, j);
    }
  }
  return std::nullopt;
}

}  // namespace

TEST(Geometry, FindSelfIntersectionOnBigPolygonsMatchesAllPairs) {
  // Random polygons of 65..400 vertices (past the all-pairs size, so the grid answers), most of
  // them self-intersecting: the grid finds the same first pair as the all-pairs scan.
  std::uint64_t seed = 12345;
  const auto next = [&seed] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  int crossing = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = 65 + static_cast<std::size_t>(next() * 335);
    Polygon poly = circle(n, 50.0f);
    const int perturbations = trial % 4;  // 0: a simple polygon
    for (int k = 0; k < perturbations; ++k) {
      const auto v = static_cast<std::size_t>(next() * double(n));
      poly[v] = Vec2(static_cast<float>(next() * 100 - 50), static_cast<float>(next() * 100 - 50));
    }
    const auto expected = allPairsReference(poly);
    crossing += expected.has_value();
    EXPECT_EQ(core::findSelfIntersection(poly), expected) << "trial " << trial << ", " << n << " vertices";
  }
  EXPECT_GT(crossing, 10);
}

TEST(Geometry, FindSelfIntersectionIsNearLinear) {
  // 200,000 vertices: the all-pairs scan made 2·10¹⁰ tests (minutes); the grid a few per edge.
  Polygon big = circle(200000, 1000.0f);
  EXPECT_FALSE(core::findSelfIntersection(big).has_value());
  std::swap(big[1000], big[150000]);  // two far-apart edges now cross the circle
  const auto hit = core::findSelfIntersection(big);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->first, 999u);
}

TEST(Geometry, CheckSimpleGivesUpOnHostileShapesWithinItsBudget) {
  // A star of 20,000 spikes: every long edge passes the centre, so a grid cannot separate them
  // and every pair would be tested (2·10⁸). With a budget the check says "too complex".
  Polygon star(20000);
  for (std::size_t i = 0; i < star.size(); ++i) {
    const double a = 2.0 * 3.14159265358979323846 * double(i) / double(star.size());
    const double r = i % 2 == 0 ? 50.0 : 0.5;
    star[i] = Vec2(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)));
  }
  const auto star_ = core::checkSimple(star, 1000000);
  EXPECT_TRUE(star_.tooComplex);
  EXPECT_FALSE(star_.crossing.has_value());
  // An ordinary outline of 200,000 vertices stays within a few tests per edge.
  const auto round = core::checkSimple(circle(200000, 1000.0f), 64 * 200000);
  EXPECT_FALSE(round.tooComplex);
  EXPECT_FALSE(round.crossing.has_value());
  // A crossing found within the budget is reported as findSelfIntersection does.
  const Polygon bowtie{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  const auto crossed = core::checkSimple(bowtie, 10);
  EXPECT_FALSE(crossed.tooComplex);
  EXPECT_EQ(crossed.crossing, core::findSelfIntersection(bowtie));
}

// Tests for libs/core/src/footprint.cpp: the union of ground-plane triangles — two triangles
// make one square, a ring of squares keeps its hole, disjoint triangles stay apart, degenerate
// triangles are dropped, collinear vertices removed and the outer rings counter-clockwise.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "throng/core/footprint.hpp"

using namespace throng::core;

namespace {

using Triangle = std::array<Vec2, 3>;

/// The two triangles of the axis-aligned square [x, x + s] × [y, y + s].
void addSquare(std::vector<Triangle>& out, float x, float y, float s) {
  out.push_back({Vec2{x, y}, Vec2{x + s, y}, Vec2{x + s, y + s}});
  out.push_back({Vec2{x, y}, Vec2{x + s, y + s}, Vec2{x, y + s}});
}

}  // namespace

TEST(Footprint, TwoTrianglesMakeOneSquare) {
  std::vector<Triangle> tris;
  addSquare(tris, 0.0f, 0.0f, 2.0f);
  const Footprint fp = unionOfTriangles(tris);
  ASSERT_EQ(fp.outer.size(), 1u);
  EXPECT_TRUE(fp.holes.empty());
  EXPECT_EQ(fp.outer[0].size(), 4u);  // the shared diagonal is gone
  EXPECT_NEAR(signedArea(fp.outer[0]), 4.0, 1e-6);  // positive: counter-clockwise
}

TEST(Footprint, RingOfSquaresKeepsItsHole) {
  std::vector<Triangle> tris;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == 1 && j == 1) continue;  // the middle square is the hole
      addSquare(tris, static_cast<float>(i), static_cast<float>(j), 1.0f);
    }
  }
  const Footprint fp = unionOfTriangles(tris);
  ASSERT_EQ(fp.outer.size(), 1u);
  ASSERT_EQ(fp.holes.size(), 1u);
  EXPECT_NEAR(signedArea(fp.outer[0]), 9.0, 1e-6);
  EXPECT_NEAR(std::abs(signedArea(fp.holes[0])), 1.0, 1e-6);
  EXPECT_EQ(fp.outer[0].size(), 4u);  // collinear vertices along the sides removed
}

TEST(Footprint, DisjointTrianglesStayApart) {
  std::vector<Triangle> tris;
  addSquare(tris, 0.0f, 0.0f, 1.0f);
  addSquare(tris, 5.0f, 0.0f, 1.0f);
  const Footprint fp = unionOfTriangles(tris);
  ASSERT_EQ(fp.outer.size(), 2u);
  for (const Polygon& p : fp.outer) EXPECT_NEAR(signedArea(p), 1.0, 1e-6);
}

TEST(Footprint, DegenerateTrianglesAreDropped) {
  std::vector<Triangle> tris{{Vec2{0, 0}, Vec2{1, 0}, Vec2{2, 0}},          // a line: no area
                             {Vec2{0, 0}, Vec2{1e-4f, 0}, Vec2{0, 1e-4f}}};  // below 1 mm²
  EXPECT_TRUE(unionOfTriangles(tris).outer.empty());
  EXPECT_TRUE(unionOfTriangles({}).outer.empty());
}

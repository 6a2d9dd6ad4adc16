// Tests for libs/crowd/src/bezier.cpp: de Casteljau evaluation, split, control box, flattening.
#include "throng/crowd/bezier.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace crowd = throng::crowd;
using throng::core::Vec2;
using throng::core::distance;

namespace {

/// Bernstein form: sum C(n,i) (1-t)^(n-i) t^i b_i, the reference the recursion must match.
Vec2 bernstein(const std::vector<Vec2>& b, double t) {
  const int n = static_cast<int>(b.size()) - 1;
  double x = 0.0, y = 0.0, binom = 1.0;
  for (int i = 0; i <= n; ++i) {
    const double w = binom * std::pow(1.0 - t, n - i) * std::pow(t, i);
    x += w * b[i].x;
    y += w * b[i].y;
    binom = binom * (n - i) / (i + 1);
  }
  return {static_cast<float>(x), static_cast<float>(y)};
}

rc::Gen<std::vector<Vec2>> genControl(int minPoints, int maxPoints) {
  return rc::gen::mapcat(rc::gen::inRange(minPoints, maxPoints + 1), [](int n) {
    return rc::gen::container<std::vector<Vec2>>(
        static_cast<std::size_t>(n), rc::gen::map(rc::gen::pair(rc::gen::inRange(-5000, 5001), rc::gen::inRange(-5000, 5001)),
                                                  [](std::pair<int, int> p) { return Vec2{p.first * 0.01f, p.second * 0.01f}; }));
  });
}

rc::Gen<float> genT() {
  return rc::gen::map(rc::gen::inRange(0, 1001), [](int v) { return v * 0.001f; });
}

}  // namespace

TEST(Bezier, EndpointsAndStraightLine) {
  const std::vector<Vec2> line{{0, 0}, {10, 4}};
  EXPECT_EQ(crowd::evaluate(line, 0.0f), Vec2(0, 0));
  EXPECT_EQ(crowd::evaluate(line, 1.0f), Vec2(10, 4));
  const Vec2 mid = crowd::evaluate(line, 0.5f);  // eq. 3.2.2.1
  EXPECT_FLOAT_EQ(mid.x, 5.0f);
  EXPECT_FLOAT_EQ(mid.y, 2.0f);
  const std::vector<Vec2> point{{3, 7}};
  EXPECT_EQ(crowd::evaluate(point, 0.3f), Vec2(3, 7));
}

TEST(Bezier, QuadraticMidpoint) {
  // b(1/2) = (b0 + 2 b1 + b2) / 4.
  const std::vector<Vec2> q{{0, 0}, {2, 4}, {4, 0}};
  const Vec2 m = crowd::evaluate(q, 0.5f);
  EXPECT_FLOAT_EQ(m.x, 2.0f);
  EXPECT_FLOAT_EQ(m.y, 2.0f);
  EXPECT_FLOAT_EQ(crowd::flatness(q), 4.0f);
}

TEST(Bezier, HighDegreeUsesHeapAndStillMatches) {
  std::vector<Vec2> b;
  for (int i = 0; i < 24; ++i) b.push_back({float(i), float((i * 7) % 5)});
  for (float t : {0.0f, 0.25f, 0.6f, 1.0f}) {
    const Vec2 p = crowd::evaluate(b, t);
    const Vec2 r = bernstein(b, t);
    EXPECT_NEAR(p.x, r.x, 1e-3f);
    EXPECT_NEAR(p.y, r.y, 1e-3f);
  }
  auto [l, r] = crowd::split(b, 0.5f);
  EXPECT_EQ(l.degree(), 23u);
  EXPECT_EQ(r.degree(), 23u);
}

RC_GTEST_PROP(Bezier, DeCasteljauMatchesBernstein, ()) {
  const auto b = *genControl(1, 10);
  const float t = *genT();
  const Vec2 p = crowd::evaluate(b, t);
  const Vec2 r = bernstein(b, t);
  RC_ASSERT(std::abs(p.x - r.x) < 1e-3f);
  RC_ASSERT(std::abs(p.y - r.y) < 1e-3f);
}

RC_GTEST_PROP(Bezier, SplitHalvesReproduceTheCurve, ()) {
  const auto b = *genControl(2, 9);
  const float t = *rc::gen::map(rc::gen::inRange(1, 1000), [](int v) { return v * 0.001f; });
  const float s = *genT();
  auto [left, right] = crowd::split(b, t);
  RC_ASSERT(left.start() == b.front());
  RC_ASSERT(right.end() == b.back());
  const Vec2 at = crowd::evaluate(b, t);
  RC_ASSERT(distance(left.end(), at) < 1e-3f);
  RC_ASSERT(left.end() == right.start());
  const Vec2 l = crowd::evaluate(left.points, s);
  const Vec2 r = crowd::evaluate(right.points, s);
  RC_ASSERT(distance(l, crowd::evaluate(b, t * s)) < 2e-3f);
  RC_ASSERT(distance(r, crowd::evaluate(b, t + (1.0f - t) * s)) < 2e-3f);
}

// The convex-hull property behind the min-max box check (§3.2.2).
RC_GTEST_PROP(Bezier, CurveLiesInsideItsControlBox, ()) {
  const auto b = *genControl(1, 10);
  const auto box = crowd::controlBox(b);
  for (int i = 0; i <= 64; ++i) {
    const Vec2 p = crowd::evaluate(b, i / 64.0f);
    RC_ASSERT(p.x >= box.min.x - 1e-3f && p.x <= box.max.x + 1e-3f);
    RC_ASSERT(p.y >= box.min.y - 1e-3f && p.y <= box.max.y + 1e-3f);
  }
}

RC_GTEST_PROP(Bezier, SampledPolylineStaysWithinChordError, ()) {
  const auto b = *genControl(2, 6);
  const float tol = *rc::gen::element(0.01f, 0.05f, 0.2f, 1.0f);
  std::vector<Vec2> poly;
  crowd::sample(b, tol, poly);
  RC_ASSERT(poly.size() >= 2u);
  RC_ASSERT(poly.front() == b.front());
  RC_ASSERT(poly.back() == b.back());
  for (int i = 0; i <= 200; ++i) {
    const Vec2 p = crowd::evaluate(b, i / 200.0f);
    float best = 1e30f;
    for (std::size_t k = 0; k + 1 < poly.size(); ++k) {
      best = std::min(best, throng::core::distanceToSegmentSq(p, poly[k], poly[k + 1]));
    }
    RC_ASSERT(std::sqrt(best) <= tol + 2e-3f);
  }
}

TEST(Bezier, SampleOfStraightLineIsTwoPoints) {
  const std::vector<Vec2> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}};  // a cubic with collinear control points
  std::vector<Vec2> poly;
  crowd::sample(line, 0.01f, poly);
  EXPECT_EQ(poly.size(), 2u);
}

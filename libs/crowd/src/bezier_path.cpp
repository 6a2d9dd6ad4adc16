// throng::crowd Bézier seek-goal paths (§3.2.2): min-max box check by recursive de Casteljau
// subdivision, and the "recompute until inside" construction of buildPath.
#include "throng/crowd/bezier_path.hpp"

#include <array>
#include <cmath>

#include "throng/core/assert.hpp"

namespace throng::crowd {

namespace {

bool verifyRec(std::span<const Vec2> control, const WalkableTest& test, int depthLeft, Vec2* scratch, int& calls) {
  ++calls;
  if (test.boxInside(controlBox(control))) return true;
  if (depthLeft <= 0) return false;
  const std::size_t n = control.size();
  std::span<Vec2> left(scratch, n);
  std::span<Vec2> right(scratch + n, n);
  splitInto(control, 0.5f, left, right);
  return verifyRec(left, test, depthLeft - 1, scratch + 2 * n, calls) &&
         verifyRec(right, test, depthLeft - 1, scratch + 2 * n, calls);
}

}  // namespace

bool verifyCurve(std::span<const Vec2> control, const WalkableTest& test, int maxDepth, int* boxTests) {
  THRONG_ASSERT(!control.empty());
  THRONG_ASSERT(maxDepth >= 0 && maxDepth <= 20);
  int calls = 0;
  bool ok = false;
  if (control.size() <= 2) {
    // Degree 0 or 1: the curve is the segment itself; check it exactly rather than its box.
    calls = 1;
    ok = test.segmentInside(control.front(), control.back());
  } else {
    // Two halves per level, kept while the left one recurses: 2 n (maxDepth + 1) points. Cubics at
    // the default depth fit on the stack.
    const std::size_t need = 2 * control.size() * (static_cast<std::size_t>(maxDepth) + 1);
    std::array<Vec2, 2 * 4 * 9> local{};
    std::vector<Vec2> heap;
    Vec2* scratch = local.data();
    if (need > local.size()) {
      heap.resize(need);
      scratch = heap.data();
    }
    ok = verifyRec(control, test, maxDepth, scratch, calls);
  }
  if (boxTests) *boxTests += calls;
  return ok;
}

namespace {

/// Control points of makeBentCubic, on the stack: candidates that fail allocate nothing.
std::array<Vec2, 4> bentCubic(Vec2 from, Vec2 to, float bend1, float bend2) {
  const Vec2 d = to - from;
  const Vec2 side = core::perp(d);  // |side| = chord length, to the left of from→to
  return {from, from + d * (1.0f / 3.0f) + side * bend1, from + d * (2.0f / 3.0f) + side * bend2, to};
}

}  // namespace

BezierCurve makeBentCubic(Vec2 from, Vec2 to, float bend1, float bend2) {
  const auto c = bentCubic(from, to, bend1, bend2);
  return BezierCurve{{c.begin(), c.end()}};
}

std::optional<BezierCurve> buildPath(Vec2 from, Vec2 to, const WalkableTest& test, const BezierPathParams& params,
                                     core::Rng& rng) {
  THRONG_ASSERT(params.maxBend >= 0.0f && params.attempts >= 0);
  THRONG_ASSERT(params.shrink > 0.0f && params.shrink < 1.0f);
  // Always exactly two draws, whatever happens next: the agent's stream stays aligned.
  const float b1 = static_cast<float>(rng.uniform(-1.0, 1.0)) * params.maxBend;
  const float b2 = static_cast<float>(rng.uniform(-1.0, 1.0)) * params.maxBend;
  if (!test.pointInside(from) || !test.pointInside(to)) return std::nullopt;
  if (core::distance(from, to) >= params.minLength && params.maxBend > 0.0f && params.attempts > 0) {
    auto tryCubic = [&](float bend1, float bend2) -> std::optional<BezierCurve> {
      const auto c = bentCubic(from, to, bend1, bend2);
      if (!verifyCurve(c, test, params.maxDepth)) return std::nullopt;
      return BezierCurve{{c.begin(), c.end()}};
    };
    // Each scale tries the drawn bend, then its mirror image (the other side of the chord), so
    // that an obstacle on the straight line is passed on whichever side is free.
    float scale = 1.0f;
    for (int k = 0; k < params.attempts; ++k, scale *= params.shrink) {
      for (const float side : {1.0f, -1.0f}) {
        if (auto c = tryCubic(side * b1 * scale, side * b2 * scale)) return c;
      }
    }
    // A drawn bend near zero (or an S) can stay on an obstacle lying across the chord: try the two
    // symmetric arcs (C shapes) at full and at one shrunk bend before giving up on curves.
    for (const float bend : {params.maxBend, params.maxBend * params.shrink}) {
      for (const float side : {1.0f, -1.0f}) {
        if (auto c = tryCubic(side * bend, side * bend)) return c;
      }
    }
  }
  // Eq. 3.2.2.1: the straight line, checked exactly.
  if (test.segmentInside(from, to)) return BezierCurve{{from, to}};
  return std::nullopt;
}

std::optional<BezierCurve> buildPath(Vec2 from, Vec2 to, std::span<const Region> corridor, const WalkableTest& test,
                                     const BezierPathParams& params, core::Rng& rng) {
  if (corridor.empty()) return buildPath(from, to, test, params, rng);
  const RegionConstrainedWalkable constrained(test, corridor);
  return buildPath(from, to, constrained, params, rng);
}

}  // namespace throng::crowd

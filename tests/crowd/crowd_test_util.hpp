// Shared generators for the crowd tests: random rooms (rectangles and L-shapes) with rectangular
// obstacles, random points on their walkable area, random star-shaped polygons.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/core/rng.hpp"
#include "throng/crowd/walkable.hpp"

namespace throng::crowd::testing {

using core::Polygon;
using core::Vec2;

inline Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

struct Layout {
  Polygon walkable;
  std::vector<Polygon> obstacles;
};

/// A room W x H (6..40 m), half of the time an L (top-right corner cut away), with 0..6 rectangular
/// obstacles 0.3..3 m wide inside it.
inline Layout randomLayout(std::uint64_t seed) {
  core::Rng rng(seed, 0, core::RngPurpose::Bench);
  const float w = static_cast<float>(rng.uniform(6.0, 40.0));
  const float h = static_cast<float>(rng.uniform(6.0, 40.0));
  Layout l;
  if (rng.uniform() < 0.5) {
    l.walkable = rect(0, 0, w, h);
  } else {
    const float cx = static_cast<float>(rng.uniform(0.3, 0.7)) * w;
    const float cy = static_cast<float>(rng.uniform(0.3, 0.7)) * h;
    l.walkable = {{0, 0}, {w, 0}, {w, cy}, {cx, cy}, {cx, h}, {0, h}};
  }
  const int n = static_cast<int>(rng.uniformInt(0, 6));
  for (int i = 0; i < n; ++i) {
    const float ow = static_cast<float>(rng.uniform(0.3, 3.0));
    const float oh = static_cast<float>(rng.uniform(0.3, 3.0));
    const float x = static_cast<float>(rng.uniform(0.0, w - ow));
    const float y = static_cast<float>(rng.uniform(0.0, h - oh));
    l.obstacles.push_back(rect(x, y, x + ow, y + oh));
  }
  return l;
}

/// Uniform point of the layout's walkable area keeping `clearance` from walls and obstacles.
inline Vec2 randomWalkablePoint(const Layout& l, const WalkableTest& test, core::Rng& rng) {
  const core::Aabb b = core::bounds(l.walkable);
  for (int tries = 0; tries < 10000; ++tries) {
    const Vec2 p{static_cast<float>(rng.uniform(b.min.x, b.max.x)), static_cast<float>(rng.uniform(b.min.y, b.max.y))};
    if (test.pointInside(p)) return p;
  }
  return l.walkable[0];
}

/// Strictly inside the walkable polygon and outside every obstacle (dense-sampling oracle).
inline bool insideLayout(const Layout& l, Vec2 p) {
  if (!core::pointInPolygon(l.walkable, p)) return false;
  for (const auto& o : l.obstacles) {
    if (core::pointInPolygon(o, p)) return false;
  }
  return true;
}

/// Star-shaped simple polygon around c: `n` vertices at increasing angles, radii in [rMin, rMax].
inline Polygon randomStar(core::Rng& rng, Vec2 c, int n, float rMin, float rMax) {
  Polygon p;
  for (int i = 0; i < n; ++i) {
    const double a = (i + rng.uniform(0.1, 0.9)) * 6.283185307179586 / n;
    const double r = rng.uniform(rMin, rMax);
    p.push_back({c.x + static_cast<float>(r * std::cos(a)), c.y + static_cast<float>(r * std::sin(a))});
  }
  return p;
}

}  // namespace throng::crowd::testing

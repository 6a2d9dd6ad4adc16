// Small worlds shared by the nav tests: rectangles, rooms with doors, pillar fields.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "throng/core/diagnostic.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav::testing {

inline Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

inline bool insideRect(Vec2 p, float x0, float y0, float x1, float y1) {
  return p.x > x0 && p.x < x1 && p.y > y0 && p.y < y1;
}

inline std::shared_ptr<const NavMesh> buildOrFail(const std::vector<Polygon>& walkable,
                                                  const std::vector<Polygon>& obstacles, NavMeshConfig config = {}) {
  auto result = NavMesh::build(walkable, obstacles, config);
  if (!result.ok()) {
    ADD_FAILURE() << core::formatAll(result.errors());
    return nullptr;
  }
  return result.value();
}

/// 20 m x 10 m room split at x = 10 by a 0.2 m wall (touching the outer edge) with a door of
/// width `door` centred at y = 5.
inline std::vector<Polygon> doorWall(float door) {
  const float lo = 5.0f - door * 0.5f;
  const float hi = 5.0f + door * 0.5f;
  return {rect(9.9f, 0.0f, 10.1f, lo), rect(9.9f, hi, 10.1f, 10.0f)};
}

/// side x side square with 1 m pillars every `spacing` metres.
inline std::vector<Polygon> pillars(float side, float spacing) {
  std::vector<Polygon> out;
  for (float x = spacing; x < side - 1.0f; x += spacing)
    for (float y = spacing; y < side - 1.0f; y += spacing) out.push_back(rect(x - 0.5f, y - 0.5f, x + 0.5f, y + 0.5f));
  return out;
}

inline float pathLength(Vec2 from, const std::vector<Vec2>& corners) {
  float len = 0.0f;
  Vec2 prev = from;
  for (Vec2 c : corners) {
    len += distance(prev, c);
    prev = c;
  }
  return len;
}

}  // namespace throng::nav::testing

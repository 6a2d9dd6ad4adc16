// Private polygon/box/segment predicates shared by the region and walkable tests (metres).
#pragma once
#include <algorithm>
#include <array>
#include <span>

#include "throng/core/geometry.hpp"

namespace throng::crowd::detail {

using core::Aabb;
using core::Vec2;

inline std::array<Vec2, 4> corners(const Aabb& b) {
  return {Vec2{b.min.x, b.min.y}, Vec2{b.max.x, b.min.y}, Vec2{b.max.x, b.max.y}, Vec2{b.min.x, b.max.y}};
}

inline Aabb grow(const Aabb& b, float d) { return Aabb{{b.min.x - d, b.min.y - d}, {b.max.x + d, b.max.y + d}}; }

inline bool boxesOverlap(const Aabb& a, const Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

/// Segment ab touches the closed box.
inline bool segmentTouchesBox(Vec2 a, Vec2 b, const Aabb& box) {
  if (box.contains(a) || box.contains(b)) return true;
  const auto c = corners(box);
  for (int i = 0; i < 4; ++i) {
    if (core::segmentsIntersect(a, b, c[i], c[(i + 1) % 4])) return true;
  }
  return false;
}

/// Some edge of the polygon touches the closed box.
inline bool boundaryTouchesBox(std::span<const Vec2> poly, const Aabb& box) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (segmentTouchesBox(poly[i], poly[(i + 1) % n], box)) return true;
  }
  return false;
}

/// The closed box lies strictly inside the polygon: a corner inside and no edge touching it.
inline bool polygonContainsBox(std::span<const Vec2> poly, const Aabb& box) {
  if (!core::pointInPolygon(poly, box.min)) return false;
  return !boundaryTouchesBox(poly, box);
}

/// The closed box and the polygon share a point.
inline bool polygonTouchesBox(std::span<const Vec2> poly, const Aabb& box) {
  if (core::pointInPolygon(poly, box.min)) return true;  // box inside polygon or overlapping
  if (box.contains(poly[0])) return true;                 // polygon inside box
  return boundaryTouchesBox(poly, box);
}

/// Squared distance between segments ab and cd (0 when they touch).
inline float segmentDistanceSq(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (core::segmentsIntersect(a, b, c, d)) return 0.0f;
  return std::min(std::min(core::distanceToSegmentSq(a, c, d), core::distanceToSegmentSq(b, c, d)),
                  std::min(core::distanceToSegmentSq(c, a, b), core::distanceToSegmentSq(d, a, b)));
}

/// Squared distance from segment ab to the polygon's boundary.
inline float segmentBoundaryDistanceSq(std::span<const Vec2> poly, Vec2 a, Vec2 b) {
  float best = 1e30f;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) best = std::min(best, segmentDistanceSq(a, b, poly[i], poly[(i + 1) % n]));
  return best;
}

}  // namespace throng::crowd::detail

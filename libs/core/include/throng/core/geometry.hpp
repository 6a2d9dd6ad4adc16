// throng::core geometry — polygons and segments in the plane (metres). Used by validation
// (simple, non-degenerate polygons), spawning (point-in-polygon, sampling) and steering (walls).
#pragma once
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "throng/core/vec2.hpp"

namespace throng::core {

using Polygon = std::vector<Vec2>;  ///< closed implicitly; any winding

struct Segment {
  Vec2 a;
  Vec2 b;
};

struct Aabb {
  Vec2 min{1e30f, 1e30f};
  Vec2 max{-1e30f, -1e30f};
  void extend(Vec2 p);
  [[nodiscard]] bool contains(Vec2 p) const;
  [[nodiscard]] bool valid() const { return min.x <= max.x && min.y <= max.y; }
};

/// Signed area (positive when counter-clockwise), m².
[[nodiscard]] double signedArea(std::span<const Vec2> poly);
[[nodiscard]] Aabb bounds(std::span<const Vec2> poly);
/// Even-odd point in polygon test; points on the boundary may go either way.
[[nodiscard]] bool pointInPolygon(std::span<const Vec2> poly, Vec2 p);
/// Proper or touching intersection of segments ab and cd.
[[nodiscard]] bool segmentsIntersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);
/// First pair of edges (i < j) that intersect, if any; nullopt for a simple polygon. Adjacent edges
/// count only when they fold back onto each other (a zero-width spike).
[[nodiscard]] std::optional<std::pair<std::size_t, std::size_t>> findSelfIntersection(std::span<const Vec2> poly);
[[nodiscard]] Vec2 closestPointOnSegment(Vec2 p, Vec2 a, Vec2 b);
[[nodiscard]] float distanceToSegmentSq(Vec2 p, Vec2 a, Vec2 b);
/// Distance from p to the polygon's boundary.
[[nodiscard]] float distanceToBoundary(std::span<const Vec2> poly, Vec2 p);
[[nodiscard]] Vec2 centroid(std::span<const Vec2> poly);
/// Ear-clipping triangulation of a simple polygon; returns index triples (CCW).
[[nodiscard]] std::vector<std::array<std::size_t, 3>> triangulate(std::span<const Vec2> poly);

}  // namespace throng::core

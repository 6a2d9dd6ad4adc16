// throng::crowd::Region — the walkable region of an interest or action point (Musse & Thalmann,
// §3.1.1, Figure 2): a disc (`radius` around `centre`) or a polygon. Read by sub-region division
// (§3.1.3), path reconstruction (§3.1.2) and region-constrained Bézier paths (§3.2.2, Figures 6-7).
// Pure geometry: reads regions, writes nothing but its results.
#pragma once
#include <span>

#include "throng/core/geometry.hpp"

namespace throng::crowd {

using core::Aabb;
using core::Polygon;
using core::Vec2;

struct Region {
  Vec2 centre;           ///< disc centre; for a polygon, the point the region stands for (its IP position) [m]
  float radius = 0.0f;   ///< disc radius [m] [Limit: >= 0]; ignored when `polygon` is not empty
  Polygon polygon;       ///< polygon region (simple, >= 3 vertices, any winding); empty for a disc

  [[nodiscard]] bool isDisc() const { return polygon.empty(); }
  [[nodiscard]] static Region disc(Vec2 c, float r) { return Region{c, r, {}}; }
  [[nodiscard]] static Region poly(Polygon p) {
    const Vec2 c = core::centroid(p);
    return Region{c, 0.0f, std::move(p)};
  }
};

/// Area of the region [m²].
[[nodiscard]] double regionArea(const Region& region);
/// Bounding box of the region.
[[nodiscard]] Aabb regionBounds(const Region& region);
/// Point p inside the region (closed disc; polygon by the even-odd rule).
[[nodiscard]] bool regionContains(const Region& region, Vec2 p);
/// Every point of the closed box lies inside the region (exact for discs and simple polygons; a box
/// touching a polygon's boundary counts as outside).
[[nodiscard]] bool regionContainsBox(const Region& region, const Aabb& box);
/// Every point of segment ab lies inside the region.
[[nodiscard]] bool regionContainsSegment(const Region& region, Vec2 a, Vec2 b);
/// Distance from p to the region: 0 inside, else to the disc rim or polygon boundary [m].
[[nodiscard]] float distanceToRegion(const Region& region, Vec2 p);

}  // namespace throng::crowd

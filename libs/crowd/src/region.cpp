// throng::crowd::Region — disc or polygon regions of IP/AP (§3.1.1): area, bounds, containment.
#include "throng/crowd/region.hpp"

#include <cmath>

#include "polygon_tests.hpp"

namespace throng::crowd {

double regionArea(const Region& region) {
  if (region.isDisc()) return 3.14159265358979323846 * double(region.radius) * double(region.radius);
  return std::abs(core::signedArea(region.polygon));
}

Aabb regionBounds(const Region& region) {
  if (region.isDisc()) {
    return Aabb{{region.centre.x - region.radius, region.centre.y - region.radius},
                {region.centre.x + region.radius, region.centre.y + region.radius}};
  }
  return core::bounds(region.polygon);
}

bool regionContains(const Region& region, Vec2 p) {
  if (region.isDisc()) return core::distance(p, region.centre) <= region.radius;
  return core::pointInPolygon(region.polygon, p);
}

bool regionContainsBox(const Region& region, const Aabb& box) {
  if (region.isDisc()) {
    // A disc is convex: the box is inside when its four corners are.
    for (const Vec2 c : detail::corners(box)) {
      if (core::distance(c, region.centre) > region.radius) return false;
    }
    return true;
  }
  return detail::polygonContainsBox(region.polygon, box);
}

bool regionContainsSegment(const Region& region, Vec2 a, Vec2 b) {
  if (region.isDisc()) return regionContains(region, a) && regionContains(region, b);
  if (!core::pointInPolygon(region.polygon, a)) return false;
  const auto& poly = region.polygon;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (core::segmentsIntersect(a, b, poly[i], poly[(i + 1) % n])) return false;
  }
  return true;
}

float distanceToRegion(const Region& region, Vec2 p) {
  if (region.isDisc()) return std::max(0.0f, core::distance(p, region.centre) - region.radius);
  if (core::pointInPolygon(region.polygon, p)) return 0.0f;
  return core::distanceToBoundary(region.polygon, p);
}

}  // namespace throng::crowd

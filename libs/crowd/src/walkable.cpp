// throng::crowd walkable oracles for the min-max box check (§3.2.2): polygons, navigation mesh,
// region corridor. Read-only queries; answers are conservative (inside is a guarantee).
#include "throng/crowd/walkable.hpp"

#include <algorithm>
#include <cmath>

#include "polygon_tests.hpp"
#include "throng/core/assert.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::crowd {

// ---- PolygonWalkable ---------------------------------------------------------------------------

PolygonWalkable::PolygonWalkable(std::vector<core::Polygon> walkable, std::vector<core::Polygon> obstacles,
                                 float clearance)
    : walkable_(std::move(walkable)), obstacles_(std::move(obstacles)), clearance_(clearance) {
  THRONG_ASSERT(clearance_ >= 0.0f);
  for (const auto& p : walkable_) walkableBounds_.push_back(core::bounds(p));
  for (const auto& p : obstacles_) obstacleBounds_.push_back(core::bounds(p));
}

bool PolygonWalkable::boxInside(const Aabb& box) const {
  const Aabb grown = detail::grow(box, clearance_);
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    if (detail::boxesOverlap(grown, obstacleBounds_[i]) && detail::polygonTouchesBox(obstacles_[i], grown)) return false;
  }
  for (std::size_t i = 0; i < walkable_.size(); ++i) {
    const Aabb& b = walkableBounds_[i];
    if (grown.min.x < b.min.x || grown.min.y < b.min.y || grown.max.x > b.max.x || grown.max.y > b.max.y) continue;
    if (detail::polygonContainsBox(walkable_[i], grown)) return true;
  }
  return false;
}

bool PolygonWalkable::segmentInside(Vec2 a, Vec2 b) const {
  const float c2 = clearance_ * clearance_;
  Aabb seg;
  seg.extend(a);
  seg.extend(b);
  const Aabb grown = detail::grow(seg, clearance_);
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    if (!detail::boxesOverlap(grown, obstacleBounds_[i])) continue;
    if (core::pointInPolygon(obstacles_[i], a)) return false;
    if (detail::segmentBoundaryDistanceSq(obstacles_[i], a, b) <= c2) return false;
  }
  for (std::size_t i = 0; i < walkable_.size(); ++i) {
    if (!core::pointInPolygon(walkable_[i], a) || !core::pointInPolygon(walkable_[i], b)) continue;
    if (detail::segmentBoundaryDistanceSq(walkable_[i], a, b) > c2) return true;
  }
  return false;
}

bool PolygonWalkable::pointInside(Vec2 p) const { return segmentInside(p, p); }

// ---- NavMeshWalkable ---------------------------------------------------------------------------

NavMeshWalkable::NavMeshWalkable(const nav::NavQuery& query, float scanSpacing, float snapTolerance)
    : query_(&query), scanSpacing_(scanSpacing), snapTolerance_(snapTolerance) {
  THRONG_ASSERT(scanSpacing_ > 0.0f && snapTolerance_ > 0.0f);
}

bool NavMeshWalkable::pointInside(Vec2 p) const {
  // Search a little wider than the tolerance so that a point just off the mesh finds its nearest
  // mesh point and is rejected by distance rather than by "nothing found".
  const auto hit = query_->nearest(p, 4.0f * snapTolerance_);
  return hit && core::distance(hit->first, p) <= snapTolerance_;
}

bool NavMeshWalkable::ray(Vec2 a, Vec2 b) const {
  if (core::distance(a, b) <= snapTolerance_) return true;  // a is on the mesh: nothing to cross
  return query_->visible(a, b);
}

bool NavMeshWalkable::segmentInside(Vec2 a, Vec2 b) const {
  return pointInside(a) && pointInside(b) && ray(a, b);
}

bool NavMeshWalkable::boxInside(const Aabb& box) const {
  const auto c = detail::corners(box);
  for (const Vec2 p : c) {
    if (!pointInside(p)) return false;
  }
  for (int i = 0; i < 4; ++i) {
    if (!ray(c[i], c[(i + 1) % 4])) return false;
  }
  if (!ray(c[0], c[2]) || !ray(c[1], c[3])) return false;
  // Scan lines find holes that neither edges nor diagonals cross. Their ends lie on the box edges,
  // which are already known to be on the mesh.
  const float w = box.max.x - box.min.x;
  const float h = box.max.y - box.min.y;
  const int nx = static_cast<int>(std::floor(w / scanSpacing_));
  const int ny = static_cast<int>(std::floor(h / scanSpacing_));
  for (int k = 1; k <= ny; ++k) {
    const float y = box.min.y + h * float(k) / float(ny + 1);
    if (!ray({box.min.x, y}, {box.max.x, y})) return false;
  }
  for (int k = 1; k <= nx; ++k) {
    const float x = box.min.x + w * float(k) / float(nx + 1);
    if (!ray({x, box.min.y}, {x, box.max.y})) return false;
  }
  return true;
}

// ---- RegionConstrainedWalkable -----------------------------------------------------------------

RegionConstrainedWalkable::RegionConstrainedWalkable(const WalkableTest& base, std::span<const Region> regions)
    : base_(&base), regions_(regions) {}

bool RegionConstrainedWalkable::boxInside(const Aabb& box) const {
  bool inRegion = regions_.empty();
  for (const Region& r : regions_) {
    if (regionContainsBox(r, box)) {
      inRegion = true;
      break;
    }
  }
  return inRegion && base_->boxInside(box);
}

namespace {

/// Where segment a + t (b − a), walked from t (a point inside `region`), leaves it: the parameter
/// of its first exit after t, at most 1 (for a disc the far root of |p(t) − c| = r; for a polygon
/// the first crossing of an edge beyond t).
float exitAlong(const Region& region, Vec2 a, Vec2 d, float t) {
  if (region.isDisc()) {
    const Vec2 f = a - region.centre;
    const float qa = core::dot(d, d), qb = 2.0f * core::dot(f, d), qc = core::dot(f, f) - region.radius * region.radius;
    if (qa < 1e-12f) return 1.0f;
    const float disc = qb * qb - 4.0f * qa * qc;
    if (disc < 0.0f) return t;
    return std::min(1.0f, (-qb + std::sqrt(disc)) / (2.0f * qa));
  }
  float exit = 1.0f;
  const auto& poly = region.polygon;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 e0 = poly[i], e = poly[(i + 1) % poly.size()] - e0;
    const float den = core::cross(d, e);
    if (std::abs(den) < 1e-12f) continue;  // parallel
    const Vec2 q = e0 - a;
    const float s = core::cross(q, e) / den;  // along the segment
    const float u = core::cross(q, d) / den;  // along the edge
    if (u >= 0.0f && u <= 1.0f && s > t + 1e-6f) exit = std::min(exit, s);
  }
  return exit;
}

}  // namespace

bool RegionConstrainedWalkable::segmentInside(Vec2 a, Vec2 b) const {
  if (!base_->segmentInside(a, b)) return false;
  if (regions_.empty()) return true;
  // Inside the corridor: covered by the union of the regions, not necessarily by one (a straight
  // line through three overlapping discs). Walk from a, each step to the farthest exit of a region
  // holding the point reached.
  const Vec2 d = b - a;
  float t = 0.0f;
  while (t < 1.0f) {
    const Vec2 p = a + d * t;
    float farthest = t;
    for (const Region& r : regions_) {
      if (regionContains(r, p)) farthest = std::max(farthest, exitAlong(r, a, d, t));
    }
    if (farthest <= t + 1e-6f) return false;  // p lies in no region, or on the rim of all that hold it
    t = farthest;
  }
  return true;
}

bool RegionConstrainedWalkable::pointInside(Vec2 p) const {
  bool inRegion = regions_.empty();
  for (const Region& r : regions_) {
    if (regionContains(r, p)) {
      inRegion = true;
      break;
    }
  }
  return inRegion && base_->pointInside(p);
}

}  // namespace throng::crowd

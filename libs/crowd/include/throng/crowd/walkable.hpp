// throng::crowd::WalkableTest — "is this box (segment, point) fully on the walkable surface?", the
// oracle of the min-max box check of Bézier paths (Musse & Thalmann, §3.2.2). Implementations over
// a Detour navigation mesh (the simulation's), over plain polygons (tests, tools) and restricted to
// a corridor of IP/AP regions (§3.1.1 Figure 4, §3.2.2 Figures 6-7). All answers are conservative:
// "inside" is a guarantee, "outside" may be a false alarm (the caller subdivides or gives up).
// Read-only; not thread-safe when the underlying NavQuery is not (use one per thread).
#pragma once
#include <span>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/crowd/region.hpp"

namespace throng::nav {
class NavQuery;
}

namespace throng::crowd {

class WalkableTest {
 public:
  virtual ~WalkableTest() = default;
  /// Every point of the closed axis-aligned box is walkable (a degenerate box is a segment or point).
  [[nodiscard]] virtual bool boxInside(const Aabb& box) const = 0;
  /// Every point of the segment ab is walkable.
  [[nodiscard]] virtual bool segmentInside(Vec2 a, Vec2 b) const = 0;
  /// The point is walkable.
  [[nodiscard]] virtual bool pointInside(Vec2 p) const = 0;
};

/// Walkable area = union of `walkable` polygons minus the `obstacles`, shrunk by `clearance`.
/// A box or segment counts as inside when it lies inside ONE walkable polygon (a box straddling two
/// overlapping walkable polygons is refused: the caller's subdivision splits it) and keeps
/// `clearance` metres from every boundary (boxes: the box grown by `clearance` on each side).
class PolygonWalkable final : public WalkableTest {
 public:
  PolygonWalkable(std::vector<core::Polygon> walkable, std::vector<core::Polygon> obstacles, float clearance = 0.0f);
  [[nodiscard]] bool boxInside(const Aabb& box) const override;
  [[nodiscard]] bool segmentInside(Vec2 a, Vec2 b) const override;
  [[nodiscard]] bool pointInside(Vec2 p) const override;

 private:
  std::vector<core::Polygon> walkable_;
  std::vector<core::Polygon> obstacles_;
  std::vector<Aabb> walkableBounds_;
  std::vector<Aabb> obstacleBounds_;
  float clearance_ = 0.0f;  ///< [m] [Limit: >= 0]
};

/// Walkable area = the navigation mesh (already eroded by the agent radius, so no extra clearance).
/// - point: its nearest mesh point is within `snapTolerance` metres;
/// - segment: both ends on the mesh and a Detour raycast a→b stays on it (NavQuery::visible);
/// - box: its 4 corners on the mesh, its 4 edges and 2 diagonals visible, plus horizontal and
///   vertical scan lines every `scanSpacing` metres across it. A hole (eroded obstacle) inside the
///   box is found when it is wider AND taller than `scanSpacing`: an obstacle of any size grows by
///   2 × agentRadius with erosion, so scanSpacing <= 2 × agentRadius finds every hole.
/// Cost: about 6 + 2 × (box size / scanSpacing) raycasts per box.
class NavMeshWalkable final : public WalkableTest {
 public:
  /// `query` must outlive this object. scanSpacing [m] [Limit: > 0]; snapTolerance [m] [Limit: > 0].
  explicit NavMeshWalkable(const nav::NavQuery& query, float scanSpacing = 0.4f, float snapTolerance = 0.01f);
  [[nodiscard]] bool boxInside(const Aabb& box) const override;
  [[nodiscard]] bool segmentInside(Vec2 a, Vec2 b) const override;
  [[nodiscard]] bool pointInside(Vec2 p) const override;

 private:
  [[nodiscard]] bool ray(Vec2 a, Vec2 b) const;
  const nav::NavQuery* query_;
  float scanSpacing_;
  float snapTolerance_;
};

/// `base` restricted to a corridor: inside when `base` says so AND the box / segment / point lies
/// inside at least one of `regions` (Figure 4: a path through IP regions avoids what lies outside
/// them). Overlapping regions form a corridor; a box straddling two of them is refused, so the
/// subdivision of verifyCurve must split it. Holds references: `base` and `regions` must outlive it.
class RegionConstrainedWalkable final : public WalkableTest {
 public:
  RegionConstrainedWalkable(const WalkableTest& base, std::span<const Region> regions);
  [[nodiscard]] bool boxInside(const Aabb& box) const override;
  [[nodiscard]] bool segmentInside(Vec2 a, Vec2 b) const override;
  [[nodiscard]] bool pointInside(Vec2 p) const override;

 private:
  const WalkableTest* base_;
  std::span<const Region> regions_;
};

}  // namespace throng::crowd

// throng::nav::DistanceField — the walking distance from every place on a NavMesh to one target
// region (an exit), computed once, answered in constant time per agent: what exit choice needs
// to compare exits for thousands of agents every second without a path search each.
//
// Method: a graph whose nodes are points on the portals (the edges shared by two polygons)
// — their end points, which are the mesh's corners where shortest paths bend, and points every
// `spacing` metres between them (at most 12 per portal) — and whose edges join the nodes of each convex polygon in
// straight lines, weighted by length (times a cost factor on stairs). Dijkstra from the target's
// polygons gives each node its distance; a point's distance is the least over the nodes of its
// polygon of the straight way there plus the node's distance. Exact where the shortest way bends
// only at corners and crosses portals at sampled points; otherwise longer by the detour to the
// nearest sample (a few centimetres per crossing at the default 1 m spacing; more right next to a
// portal longer than 11 m, whose nodes lie further apart). Works on flat and on
// layered (multi-level) meshes alike. Closed polygons (a closed door: no kWalkFlag, NavMesh::setClosed)
// are left out, so the way goes round them or does not exist; a field reflects the flags as they
// were when it was built (rebuild it after doors close or open). Immutable after build; safe to
// read from any thread.
#pragma once
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {

/// Where the distances are measured to: a disc (`radius` > 0 around `centre`) or a polygon on the
/// floor at `height` — the same region a door cut takes out of the mesh (CutRegion, navmesh.hpp).
using FieldTarget = CutRegion;

struct DistanceFieldConfig {
  float spacing = 1.0f;    ///< most distance between two nodes on a portal [m] [Limit: > 0]
  float stairCost = 1.0f;  ///< a metre on a stair polygon (kStairArea) costs this many metres [Limit: >= 1]
  /// A target region off the mesh (an exit drawn beyond the eroded edge of the floor) is reached
  /// from the polygons within this distance of it [m] (as goal targets are snapped, 3 m).
  float snap = 3.0f;
};

class DistanceField {
 public:
  static constexpr float kUnreachable = std::numeric_limits<float>::infinity();

  DistanceField() = default;
  /// Builds the field of `target` over the open polygons of `mesh` (those with kWalkFlag).
  /// Deterministic: the same mesh, flags and target give the same distances. An empty field (no
  /// open polygon near the target) answers kUnreachable everywhere.
  static DistanceField build(const NavMesh& mesh, const FieldTarget& target, const DistanceFieldConfig& config = {});

  /// Walking distance [m] from `p` on polygon `ref` to the target; kUnreachable when `ref` is not a
  /// polygon of the mesh or no way leads there.
  [[nodiscard]] float at(Vec2 p, PolyRef ref) const;
  /// Largest finite distance of any node [m] (0 for an empty field).
  [[nodiscard]] float maxDistance() const { return maxDistance_; }
  [[nodiscard]] bool empty() const { return targetPolys_.empty(); }

  /// What build() gathers about a portal before the distances are known (nodes [first, first + count)).
  struct Span {
    Vec2 left, right;
    std::uint32_t first = 0, count = 0;
  };

 private:
  /// A portal of a polygon: its segment, the least distance of its nodes, its nodes.
  struct Portal {
    Vec2 left, right;
    float least = kUnreachable;
    std::uint32_t first = 0, count = 0;
  };
  using Heap = std::priority_queue<std::pair<float, std::uint32_t>, std::vector<std::pair<float, std::uint32_t>>, std::greater<>>;
  void dijkstra(Heap& heap, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& nodePolys);
  void packPortals(const std::vector<std::vector<Span>>& portalsOf);
  /// Flat polygon index of `ref`, or -1.
  [[nodiscard]] std::int64_t polyIndex(PolyRef ref) const;
  [[nodiscard]] float toTarget(Vec2 p) const;

  const dtNavMesh* mesh_ = nullptr;
  std::vector<std::uint32_t> tileBase_;              ///< first flat polygon index of each tile
  std::vector<std::uint32_t> polyNodeOffset_{0};     ///< while building: polygon i's nodes [offset[i], offset[i+1])
  std::vector<std::uint32_t> polyNodes_;             ///< while building: node indices
  std::vector<std::uint32_t> portalOffset_{0};       ///< polygon i's portals: [offset[i], offset[i+1])
  std::vector<Portal> portals_;
  std::vector<float> polyCost_;                      ///< cost per metre inside polygon i
  std::vector<std::uint8_t> targetPolys_;            ///< 1: the polygon touches the target (direct way)
  std::vector<float> nodeX_, nodeY_, nodeDist_;
  FieldTarget target_;
  float maxDistance_ = 0.0f;
};

}  // namespace throng::nav

// throng::nav::DistanceField (distance_field.hpp): portal nodes of a built Detour mesh, the target's
// polygons, Dijkstra over the straight ways inside each convex polygon, and the per-point lookup.
// Polygons are visited in (tile index, polygon index) order and the heap breaks ties by node
// index, so the distances are the same on every run and thread count.
#include "throng/nav/distance_field.hpp"

#include <DetourNavMesh.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

#include "navmesh_data.hpp"

namespace throng::nav {
namespace {

/// How far vertically a layered mesh's polygon may lie from the target's floor to count as its [m].
constexpr float kTargetLevel = 2.0f;

float distanceToRegion(const FieldTarget& t, Vec2 p) {
  if (!t.polygon.empty()) {
    if (core::pointInPolygon(t.polygon, p)) return 0.0f;
    return core::distanceToBoundary(t.polygon, p);
  }
  return std::max(0.0f, core::length(p - t.centre) - t.radius);
}

/// Distance between a convex mesh polygon and the target region (0 when they overlap).
float polygonToRegion(const FieldTarget& t, const Polygon& poly) {
  float d = 1e30f;
  for (const Vec2& v : poly) d = std::min(d, distanceToRegion(t, v));
  if (d == 0.0f) return 0.0f;
  if (t.polygon.empty()) {
    if (core::pointInPolygon(poly, t.centre)) return 0.0f;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const float e = std::sqrt(core::distanceToSegmentSq(t.centre, poly[i], poly[(i + 1) % poly.size()]));
      d = std::min(d, std::max(0.0f, e - t.radius));
    }
    return d;
  }
  for (const Vec2& v : t.polygon) {
    if (core::pointInPolygon(poly, v)) return 0.0f;
    d = std::min(d, core::distanceToBoundary(poly, v));
  }
  return d;
}

/// Polygon `ref`'s index in (tile, polygon) order, tile t's polygons starting at tileBase[t]; -1
/// for a reference outside the mesh.
std::int64_t flatIndex(const dtNavMesh& mesh, const std::vector<std::uint32_t>& tileBase, std::size_t count, dtPolyRef ref) {
  unsigned int salt = 0, it = 0, ip = 0;
  mesh.decodePolyId(ref, salt, it, ip);
  if (it >= tileBase.size()) return -1;
  const std::size_t i = tileBase[it] + ip;
  const std::size_t end = it + 1 < tileBase.size() ? tileBase[it + 1] : count;
  return i < end ? static_cast<std::int64_t>(i) : -1;
}

struct MeshPolygon {
  const dtMeshTile* tile = nullptr;
  const dtPoly* poly = nullptr;
};

/// The graph being built: nodes on portals, each lying in the two polygons the portal joins.
struct Builder {
  const dtNavMesh& mesh;
  std::vector<std::uint32_t> tileBase;
  std::vector<MeshPolygon> polys;
  std::vector<std::vector<std::uint32_t>> nodesOf;  ///< per polygon
  std::vector<float> x, y;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> nodePolys;

  explicit Builder(const dtNavMesh& m) : mesh(m) {
    for (int t = 0; t < mesh.getMaxTiles(); ++t) {
      tileBase.push_back(static_cast<std::uint32_t>(polys.size()));
      const dtMeshTile* tile = mesh.getTile(t);
      if (tile == nullptr || tile->header == nullptr) continue;
      for (int p = 0; p < tile->header->polyCount; ++p) polys.push_back({tile, &tile->polys[p]});
    }
    nodesOf.resize(polys.size());
  }

  [[nodiscard]] std::int64_t indexOf(dtPolyRef ref) const { return flatIndex(mesh, tileBase, polys.size(), ref); }

  [[nodiscard]] bool ground(std::size_t i) const { return polys[i].poly->getType() == DT_POLYTYPE_GROUND; }

  [[nodiscard]] Polygon outline(std::size_t i) const {
    const MeshPolygon& m = polys[i];
    Polygon out;
    for (int k = 0; k < m.poly->vertCount; ++k) out.push_back(detail::fromRecast(&m.tile->verts[m.poly->verts[k] * 3]));
    return out;
  }

  /// Nodes along the portal of link `l` of polygon `a` (to polygon `b`): its ends and points at
  /// most `spacing` apart, each in both polygons.
  void addPortal(std::size_t a, std::size_t b, const dtLink& l, float spacing) {
    const MeshPolygon& m = polys[a];
    const int n = m.poly->vertCount;
    const Vec2 va = detail::fromRecast(&m.tile->verts[m.poly->verts[l.edge] * 3]);
    const Vec2 vb = detail::fromRecast(&m.tile->verts[m.poly->verts[(l.edge + 1) % n] * 3]);
    Vec2 left = va, right = vb;
    if (l.side != 0xff && (l.bmin != 0 || l.bmax != 255)) {  // a link across tiles: part of the edge
      const float s = 1.0f / 255.0f;
      left = va + (vb - va) * (static_cast<float>(l.bmin) * s);
      right = va + (vb - va) * (static_cast<float>(l.bmax) * s);
    }
    const float len = core::length(right - left);
    const int samples = std::max(2, static_cast<int>(std::ceil(len / spacing)) + 1);
    for (int k = 0; k < samples; ++k) {
      const Vec2 p = left + (right - left) * (static_cast<float>(k) / static_cast<float>(samples - 1));
      const auto node = static_cast<std::uint32_t>(x.size());
      x.push_back(p.x);
      y.push_back(p.y);
      nodePolys.emplace_back(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
      nodesOf[a].push_back(node);
      nodesOf[b].push_back(node);
    }
  }

  void addPortals(float spacing) {
    for (std::size_t a = 0; a < polys.size(); ++a) {
      if (!ground(a)) continue;
      const MeshPolygon& m = polys[a];
      for (unsigned int k = m.poly->firstLink; k != DT_NULL_LINK; k = m.tile->links[k].next) {
        const dtLink& l = m.tile->links[k];
        const std::int64_t b = indexOf(l.ref);
        // Each portal once, from the polygon with the lower index (links come in pairs).
        if (b < 0 || static_cast<std::size_t>(b) <= a || !ground(static_cast<std::size_t>(b))) continue;
        addPortal(a, static_cast<std::size_t>(b), l, spacing);
      }
    }
  }
};

}  // namespace

DistanceField DistanceField::build(const NavMesh& navMesh, const FieldTarget& target, const DistanceFieldConfig& config) {
  DistanceField f;
  f.target_ = target;
  if (navMesh.detour() == nullptr) return f;
  const dtNavMesh& mesh = *navMesh.detour();
  Builder b(mesh);
  b.addPortals(std::max(config.spacing, 0.05f));
  const std::size_t polyCount = b.polys.size();
  f.mesh_ = &mesh;
  f.tileBase_ = b.tileBase;
  f.polyCost_.assign(polyCount, 1.0f);
  f.targetPolys_.assign(polyCount, 0);
  for (std::size_t i = 0; i < polyCount; ++i) {
    f.polyNodes_.insert(f.polyNodes_.end(), b.nodesOf[i].begin(), b.nodesOf[i].end());
    f.polyNodeOffset_.push_back(static_cast<std::uint32_t>(f.polyNodes_.size()));
    if (b.ground(i) && b.polys[i].poly->getArea() == kStairArea) f.polyCost_[i] = std::max(1.0f, config.stairCost);
  }
  // The target's polygons: those it overlaps on its floor, else the nearest within `snap`.
  std::vector<float> gap(polyCount, 1e30f);
  float nearest = 1e30f;
  for (std::size_t i = 0; i < polyCount; ++i) {
    if (!b.ground(i)) continue;
    const MeshPolygon& m = b.polys[i];
    if (navMesh.layered()) {
      float lo = 1e30f, hi = -1e30f;
      for (int k = 0; k < m.poly->vertCount; ++k) {
        lo = std::min(lo, m.tile->verts[m.poly->verts[k] * 3 + 1]);
        hi = std::max(hi, m.tile->verts[m.poly->verts[k] * 3 + 1]);
      }
      if (target.height < lo - kTargetLevel || target.height > hi + kTargetLevel) continue;
    }
    gap[i] = polygonToRegion(target, b.outline(i));
    nearest = std::min(nearest, gap[i]);
  }
  if (nearest > config.snap) {
    f.targetPolys_.clear();
    f.polyNodes_.clear();
    f.polyNodeOffset_.assign(1, 0);
    return f;  // nothing reaches the target: empty
  }
  const float accept = nearest <= 1e-4f ? 1e-4f : nearest + 0.5f;
  for (std::size_t i = 0; i < polyCount; ++i) f.targetPolys_[i] = gap[i] <= accept ? 1 : 0;
  f.nodeX_ = std::move(b.x);
  f.nodeY_ = std::move(b.y);
  f.nodeDist_.assign(f.nodeX_.size(), kUnreachable);
  // Dijkstra from the target polygons' nodes (the straight way to the region).
  using Entry = std::pair<float, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  for (std::size_t i = 0; i < polyCount; ++i) {
    if (f.targetPolys_[i] == 0) continue;
    for (std::uint32_t k = f.polyNodeOffset_[i]; k < f.polyNodeOffset_[i + 1]; ++k) {
      const std::uint32_t n = f.polyNodes_[k];
      const float d = distanceToRegion(target, {f.nodeX_[n], f.nodeY_[n]}) * f.polyCost_[i];
      if (d < f.nodeDist_[n]) {
        f.nodeDist_[n] = d;
        heap.emplace(d, n);
      }
    }
  }
  while (!heap.empty()) {
    const auto [d, n] = heap.top();
    heap.pop();
    if (d > f.nodeDist_[n]) continue;
    f.maxDistance_ = std::max(f.maxDistance_, d);
    for (const std::uint32_t poly : {b.nodePolys[n].first, b.nodePolys[n].second}) {
      const float cost = f.polyCost_[poly];
      for (std::uint32_t k = f.polyNodeOffset_[poly]; k < f.polyNodeOffset_[poly + 1]; ++k) {
        const std::uint32_t m = f.polyNodes_[k];
        const float nd = d + cost * std::hypot(f.nodeX_[m] - f.nodeX_[n], f.nodeY_[m] - f.nodeY_[n]);
        if (nd < f.nodeDist_[m]) {
          f.nodeDist_[m] = nd;
          heap.emplace(nd, m);
        }
      }
    }
  }
  return f;
}

std::int64_t DistanceField::polyIndex(PolyRef ref) const {
  if (mesh_ == nullptr || ref == 0) return -1;
  return flatIndex(*mesh_, tileBase_, polyCost_.size(), static_cast<dtPolyRef>(ref));
}

float DistanceField::toTarget(Vec2 p) const { return distanceToRegion(target_, p); }

float DistanceField::at(Vec2 p, PolyRef ref) const {
  const std::int64_t i = polyIndex(ref);
  if (i < 0 || targetPolys_.empty()) return kUnreachable;
  const auto poly = static_cast<std::size_t>(i);
  const float cost = polyCost_[poly];
  float best = targetPolys_[poly] != 0 ? toTarget(p) * cost : kUnreachable;
  for (std::uint32_t k = polyNodeOffset_[poly]; k < polyNodeOffset_[poly + 1]; ++k) {
    const std::uint32_t n = polyNodes_[k];
    best = std::min(best, nodeDist_[n] + cost * std::hypot(nodeX_[n] - p.x, nodeY_[n] - p.y));
  }
  return best;
}

}  // namespace throng::nav

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

/// Most nodes on one portal: a long portal (open floor cut into 24 m tiles) gets them further apart
/// than `spacing`, which keeps lookups cheap (a lookup visits a portal's nodes) at the price of a
/// longer way for an agent right next to it (at most about half the gap).
constexpr int kMostSamples = 12;

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
  using Span = DistanceField::Span;
  std::vector<std::vector<Span>> portalsOf;  ///< per polygon

  explicit Builder(const dtNavMesh& m) : mesh(m) {
    for (int t = 0; t < mesh.getMaxTiles(); ++t) {
      tileBase.push_back(static_cast<std::uint32_t>(polys.size()));
      const dtMeshTile* tile = mesh.getTile(t);
      if (tile == nullptr || tile->header == nullptr) continue;
      for (int p = 0; p < tile->header->polyCount; ++p) polys.push_back({tile, &tile->polys[p]});
    }
    nodesOf.resize(polys.size());
    portalsOf.resize(polys.size());
  }

  [[nodiscard]] std::int64_t indexOf(dtPolyRef ref) const { return flatIndex(mesh, tileBase, polys.size(), ref); }

  [[nodiscard]] bool ground(std::size_t i) const { return polys[i].poly->getType() == DT_POLYTYPE_GROUND; }
  /// Ground one may walk on: not a closed door's polygon (NavMesh::setClosed takes kWalkFlag away).
  [[nodiscard]] bool open(std::size_t i) const { return ground(i) && (polys[i].poly->flags & kWalkFlag) != 0; }

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
    const int samples = std::clamp(static_cast<int>(std::ceil(len / spacing)) + 1, 2, kMostSamples);
    const Span span{left, right, static_cast<std::uint32_t>(x.size()), static_cast<std::uint32_t>(samples)};
    portalsOf[a].push_back(span);
    portalsOf[b].push_back(span);
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
      if (!open(a)) continue;
      const MeshPolygon& m = polys[a];
      for (unsigned int k = m.poly->firstLink; k != DT_NULL_LINK; k = m.tile->links[k].next) {
        const dtLink& l = m.tile->links[k];
        const std::int64_t b = indexOf(l.ref);
        // Each portal once, from the polygon with the lower index (links come in pairs).
        if (b < 0 || static_cast<std::size_t>(b) <= a || !open(static_cast<std::size_t>(b))) continue;
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
    if (!b.open(i)) continue;
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
  Heap heap;
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
  f.dijkstra(heap, b.nodePolys);
  f.packPortals(b.portalsOf);
  return f;
}

void DistanceField::dijkstra(Heap& heap, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& nodePolys) {
  DistanceField& f = *this;
  while (!heap.empty()) {
    const auto [d, n] = heap.top();
    heap.pop();
    if (d > f.nodeDist_[n]) continue;
    f.maxDistance_ = std::max(f.maxDistance_, d);
    for (const std::uint32_t poly : {nodePolys[n].first, nodePolys[n].second}) {
      const float cost = f.polyCost_[poly];
      for (std::uint32_t k = f.polyNodeOffset_[poly]; k < f.polyNodeOffset_[poly + 1]; ++k) {
        const std::uint32_t m = f.polyNodes_[k];
        const float dx = f.nodeX_[m] - f.nodeX_[n], dy = f.nodeY_[m] - f.nodeY_[n];
        const float nd = d + cost * std::sqrt(dx * dx + dy * dy);
        if (nd < f.nodeDist_[m]) {
          f.nodeDist_[m] = nd;
          heap.emplace(nd, m);
        }
      }
    }
  }
}

void DistanceField::packPortals(const std::vector<std::vector<Span>>& portalsOf) {
  // Lookups go portal by portal (its segment bounds how near its nodes can be), so the node lists
  // used by Dijkstra are no longer needed.
  portalOffset_.assign(1, 0);
  for (const auto& spans : portalsOf) {
    for (const Span& s : spans) {
      float least = kUnreachable;
      for (std::uint32_t n = s.first; n < s.first + s.count; ++n) least = std::min(least, nodeDist_[n]);
      portals_.push_back({s.left, s.right, least, s.first, s.count});
    }
    portalOffset_.push_back(static_cast<std::uint32_t>(portals_.size()));
  }
  polyNodes_ = {};
  polyNodeOffset_ = {};
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
  // Portal by portal, the most promising first; a portal whose segment alone is farther than the
  // best way found is skipped with all its nodes.
  const std::uint32_t first = portalOffset_[poly], last = portalOffset_[poly + 1];
  constexpr std::uint32_t kSorted = 16;
  float bound[kSorted];
  std::uint32_t order[kSorted];
  const std::uint32_t count = std::min(last - first, kSorted);
  for (std::uint32_t k = 0; k < count; ++k) {
    const Portal& q = portals_[first + k];
    bound[k] = q.least + cost * std::sqrt(core::distanceToSegmentSq(p, q.left, q.right));
    order[k] = k;
  }
  for (std::uint32_t k = 1; k < count; ++k) {  // insertion sort: a handful of portals
    for (std::uint32_t j = k; j > 0 && bound[order[j]] < bound[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  }
  auto visit = [&](const Portal& q) {
    for (std::uint32_t n = q.first; n < q.first + q.count; ++n) {
      const float dx = nodeX_[n] - p.x, dy = nodeY_[n] - p.y;
      best = std::min(best, nodeDist_[n] + cost * std::sqrt(dx * dx + dy * dy));
    }
  };
  for (std::uint32_t k = 0; k < count; ++k) {
    if (bound[order[k]] >= best) break;
    visit(portals_[first + order[k]]);
  }
  for (std::uint32_t k = first + count; k < last; ++k) visit(portals_[k]);  // beyond 16 portals: all of them
  return best;
}

}  // namespace throng::nav

// throng::nav::NavQuery — per-thread queries on a NavMesh: nearest point, string-pulled paths,
// moves that slide along the mesh boundary, reachability, line of sight, and deterministic
// area-weighted random points. Reads the immutable NavMesh; writes only its own Detour node pool.
#include <DetourCommon.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "navmesh_data.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {
namespace detail {

dtPolyRef snap(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, const float extents[3],
               float snapped[3]) {
  float centre[3];
  toRecast(p, centre);
  dtPolyRef ref = 0;
  if (dtStatusFailed(query.findNearestPoly(centre, extents, &filter, &ref, snapped))) return 0;
  return ref;
}

PathStatus straighten(const dtNavMeshQuery& query, const float start[3], const float end[3],
                      const dtPolyRef* path, int pathCount, bool partial, std::vector<Vec2>& corners) {
  corners.clear();
  if (pathCount <= 0) return PathStatus::Failed;
  float target[3];
  dtVcopy(target, end);
  if (partial) {
    // Clamp the target to the last polygon reached so the path ends at the closest point.
    bool inside = false;
    query.closestPointOnPoly(path[pathCount - 1], end, target, &inside);
  }
  float straight[kMaxStraightCorners * 3];
  int count = 0;
  const dtStatus status =
      query.findStraightPath(start, target, path, pathCount, straight, nullptr, nullptr, &count, kMaxStraightCorners);
  if (dtStatusFailed(status) || count == 0) return PathStatus::Failed;
  corners.reserve(static_cast<std::size_t>(count));
  for (int i = 1; i < count; ++i) corners.push_back(fromRecast(&straight[i * 3]));
  if (corners.empty()) corners.push_back(fromRecast(target));  // start and target coincide
  return (partial || dtStatusDetail(status, DT_BUFFER_TOO_SMALL)) ? PathStatus::Partial : PathStatus::Complete;
}

}  // namespace detail

NavQuery::NavQuery(std::shared_ptr<const NavMesh> mesh, int maxNodes) : mesh_(std::move(mesh)) {
  query_ = dtAllocNavMeshQuery();
  query_->init(mesh_->detour(), std::clamp(maxNodes, 16, 65535));
  filter_ = new dtQueryFilter();
}

NavQuery::~NavQuery() {
  dtFreeNavMeshQuery(query_);
  delete filter_;
}

std::optional<std::pair<Vec2, PolyRef>> NavQuery::nearest(Vec2 p, float searchRadius) const {
  const float r = std::max(searchRadius, 0.0f);
  const float extents[3] = {r, 1.0f, r};
  float snapped[3];
  const dtPolyRef ref = detail::snap(*query_, *filter_, p, extents, snapped);
  if (ref == 0) return std::nullopt;
  const Vec2 q = detail::fromRecast(snapped);
  if (lengthSq(q - p) > r * r) return std::nullopt;  // the search box's corners reach beyond r
  return std::make_pair(q, static_cast<PolyRef>(ref));
}

PathStatus NavQuery::findPath(Vec2 from, Vec2 to, std::vector<Vec2>& corners) const {
  corners.clear();
  float start[3];
  float end[3];
  const dtPolyRef startRef = detail::snap(*query_, *filter_, from, detail::kSnapExtents, start);
  if (startRef == 0) return PathStatus::Failed;
  const dtPolyRef endRef = detail::snap(*query_, *filter_, to, detail::kSnapExtents, end);
  if (endRef == 0) {
    // Target far off the mesh: no path toward it; stay where we are.
    corners.push_back(detail::fromRecast(start));
    return PathStatus::Partial;
  }
  // Detour's sliced search run to completion rather than dtNavMeshQuery::findPath: the two A*
  // implementations can pick different (equally valid) corridors, and a path must not depend on
  // whether it came from here or from the time-sliced PathQueue.
  dtPolyRef path[detail::kMaxPathPolys];
  int count = 0;
  dtStatus status = query_->initSlicedFindPath(startRef, endRef, start, end, filter_, 0);
  while (dtStatusInProgress(status)) status = query_->updateSlicedFindPath(1 << 30, nullptr);
  if (dtStatusFailed(status)) return PathStatus::Failed;
  status = query_->finalizeSlicedFindPath(path, &count, detail::kMaxPathPolys);
  if (dtStatusFailed(status) || count == 0) return PathStatus::Failed;
  const bool partial = dtStatusDetail(status, DT_PARTIAL_RESULT) || path[count - 1] != endRef;
  return detail::straighten(*query_, start, end, path, count, partial, corners);
}

Vec2 NavQuery::moveAlongSurface(Vec2 from, Vec2 to, PolyRef& ref) const {
  Vec2 start = from;
  if (ref == 0 || !query_->isValidPolyRef(static_cast<dtPolyRef>(ref), filter_)) {
    const auto snapped = nearest(from, 2.0f);
    if (!snapped) {
      ref = 0;
      return from;
    }
    start = snapped->first;
    ref = snapped->second;
  }
  float s[3];
  float e[3];
  float result[3];
  detail::toRecast(start, s);
  detail::toRecast(to, e);
  constexpr int kMaxVisited = 16;
  dtPolyRef visited[kMaxVisited];
  int visitedCount = 0;
  const dtStatus status = query_->moveAlongSurface(static_cast<dtPolyRef>(ref), s, e, filter_, result, visited,
                                                   &visitedCount, kMaxVisited);
  if (dtStatusFailed(status)) return start;
  if (visitedCount > 0) ref = visited[visitedCount - 1];
  return detail::fromRecast(result);
}

bool NavQuery::reachable(Vec2 from, Vec2 to) const {
  std::vector<Vec2> corners;
  return findPath(from, to, corners) == PathStatus::Complete;
}

bool NavQuery::visible(Vec2 a, Vec2 b) const {
  float start[3];
  const dtPolyRef startRef = detail::snap(*query_, *filter_, a, detail::kSnapExtents, start);
  if (startRef == 0) return false;
  float s[3];
  float e[3];
  detail::toRecast(a, s);
  detail::toRecast(b, e);
  float t = 0.0f;
  float normal[3];
  constexpr int kMaxRayPolys = 256;
  dtPolyRef path[kMaxRayPolys];
  int count = 0;
  const dtStatus status = query_->raycast(startRef, s, e, filter_, &t, normal, path, &count, kMaxRayPolys);
  if (dtStatusFailed(status) || dtStatusDetail(status, DT_BUFFER_TOO_SMALL)) return false;
  return t == FLT_MAX;
}

std::optional<Vec2> NavQuery::randomPoint(float r0, float r1, float r2) const {
  const auto& areas = detail::data(*mesh_).areas;
  if (areas.empty()) return std::nullopt;
  auto unit = [](float r) { return std::clamp(std::isfinite(r) ? r : 0.0f, 0.0f, 0.99999994f); };
  // r0 picks a polygon with probability proportional to its area.
  const double total = areas.back().cumulativeArea;
  const double pick = static_cast<double>(unit(r0)) * total;
  auto it = std::upper_bound(areas.begin(), areas.end(), pick,
                             [](double v, const detail::AreaEntry& e) { return v < e.cumulativeArea; });
  if (it == areas.end()) it = std::prev(areas.end());
  const dtMeshTile* tile = nullptr;
  const dtPoly* poly = nullptr;
  mesh_->detour()->getTileAndPolyByRefUnsafe(it->ref, &tile, &poly);
  // r1 picks a triangle of the polygon's fan by area and is then rescaled to [0,1) within it;
  // with r2 it places a uniform point in that triangle (Osada et al. 2002, eq. 1).
  const float* v0 = &tile->verts[poly->verts[0] * 3];
  double fanArea = 0.0;
  double triAreas[DT_VERTS_PER_POLYGON] = {};
  for (int k = 2; k < poly->vertCount; ++k) {
    const float* a = &tile->verts[poly->verts[k - 1] * 3];
    const float* b = &tile->verts[poly->verts[k] * 3];
    triAreas[k] = std::abs(dtTriArea2D(v0, a, b)) * 0.5;
    fanArea += triAreas[k];
  }
  double s = static_cast<double>(unit(r1)) * fanArea;
  int tri = poly->vertCount - 1;
  for (int k = 2; k < poly->vertCount; ++k) {
    if (s < triAreas[k] || k == poly->vertCount - 1) {
      tri = k;
      break;
    }
    s -= triAreas[k];
  }
  const double u = triAreas[tri] > 0.0 ? std::clamp(s / triAreas[tri], 0.0, 1.0) : 0.0;
  const double v = std::sqrt(static_cast<double>(unit(r2)));
  const float* a = &tile->verts[poly->verts[tri - 1] * 3];
  const float* b = &tile->verts[poly->verts[tri] * 3];
  const double wa = 1.0 - v;
  const double wb = (1.0 - u) * v;
  const double wc = u * v;
  return Vec2{static_cast<float>(wa * v0[0] + wb * a[0] + wc * b[0]),
              static_cast<float>(wa * v0[2] + wb * a[2] + wc * b[2])};
}

}  // namespace throng::nav

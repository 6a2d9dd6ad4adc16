// throng::nav::NavQuery — per-thread queries on a NavMesh: nearest point, string-pulled paths,
// moves that slide along the mesh boundary, reachability, line of sight, and deterministic
// area-weighted random points. Reads the immutable NavMesh; writes only its own Detour node pool.
//
// Layered (terrain) meshes: the height-taking overloads pick the level by searching ±kLevelSearch
// around the given height; the overloads without a height search at height 0 with Detour's
// default 1 m vertical extent, exactly as on flat meshes (so flat results never change).
// moveAlongSurface follows polygon links from a valid `ref` and never re-snaps, so it stays on
// the level it is on; only when `ref` is 0 or stale does it snap, at height 0 (ground floor).
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
  return snap(query, filter, p, 0.0f, extents, snapped);
}

dtPolyRef snap(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, float height,
               const float extents[3], float snapped[3]) {
  float centre[3];
  toRecast(p, height, centre);
  dtPolyRef ref = 0;
  if (dtStatusFailed(query.findNearestPoly(centre, extents, &filter, &ref, snapped))) return 0;
  return ref;
}

dtPolyRef snapLevel(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, float height,
                    const float extents[3], float snapped[3]) {
  float centre[3];
  toRecast(p, height, centre);
  constexpr int kMaxPolys = 128;
  dtPolyRef polys[kMaxPolys];
  int count = 0;
  if (dtStatusFailed(query.queryPolygons(centre, extents, &filter, polys, &count, kMaxPolys))) return 0;
  dtPolyRef best = 0;
  float bestD = 0.0f;
  for (int i = 0; i < count; ++i) {
    float c[3];
    if (dtStatusFailed(query.closestPointOnPoly(polys[i], centre, c, nullptr))) continue;
    const float dy = c[1] - height;
    if (std::abs(dy) > extents[1]) continue;  // the polygon is near, but not at this level
    const float d = dtVdistSqr(c, centre);
    if (best == 0 || d < bestD) {
      best = polys[i];
      bestD = d;
      dtVcopy(snapped, c);
    }
  }
  return best;
}

dtPolyRef snapEnd(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, const EndSearch& search,
                  float snapped[3]) {
  return search.layered ? snapLevel(query, filter, p, search.height, search.extents, snapped)
                        : snap(query, filter, p, search.height, search.extents, snapped);
}

/// Whether the straight segment a → b (at `height`, from polygon `startRef`) stays on the mesh:
/// Detour's raycast reaches b without hitting a boundary edge.
bool rayStaysOnMesh(const dtNavMeshQuery& query, const dtQueryFilter& filter, dtPolyRef startRef, Vec2 a, Vec2 b,
                    float height) {
  float s[3];
  float e[3];
  toRecast(a, height, s);
  toRecast(b, height, e);
  float t = 0.0f;
  float normal[3];
  constexpr int kMaxRayPolys = 256;
  dtPolyRef path[kMaxRayPolys];
  int count = 0;
  const dtStatus status = query.raycast(startRef, s, e, &filter, &t, normal, path, &count, kMaxRayPolys);
  if (dtStatusFailed(status) || dtStatusDetail(status, DT_BUFFER_TOO_SMALL)) return false;
  return t == FLT_MAX;
}

PathStatus straighten(const dtNavMeshQuery& query, const float start[3], const float end[3],
                      const dtPolyRef* path, int pathCount, bool partial, std::vector<Vec2>& corners,
                      std::vector<float>* heights) {
  corners.clear();
  if (heights != nullptr) heights->clear();
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
  if (heights != nullptr) {
    for (int i = 1; i < count; ++i) heights->push_back(straight[i * 3 + 1]);
  }
  if (corners.empty()) {  // start and target coincide
    corners.push_back(fromRecast(target));
    if (heights != nullptr) heights->push_back(target[1]);
  }
  return (partial || dtStatusDetail(status, DT_BUFFER_TOO_SMALL)) ? PathStatus::Partial : PathStatus::Complete;
}

}  // namespace detail

namespace {

// findPath with the ends searched as `fromSearch` / `toSearch` say.
PathStatus findPathFrom(dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 from,
                        const detail::EndSearch& fromSearch, Vec2 to, const detail::EndSearch& toSearch,
                        std::vector<Vec2>& corners) {
  corners.clear();
  float start[3];
  float end[3];
  const dtPolyRef startRef = detail::snapEnd(query, filter, from, fromSearch, start);
  if (startRef == 0) return PathStatus::Failed;
  const dtPolyRef endRef = detail::snapEnd(query, filter, to, toSearch, end);
  if (endRef == 0) {
    // Target far off the mesh: no path toward it; stay where we are.
    corners.push_back(detail::fromRecast(start));
    return PathStatus::Partial;
  }
  // Detour's sliced search run to completion rather than dtNavMeshQuery::findPath: the two A*
  // implementations can pick different (equally valid) corridors, and a path must not depend on
  // whether it came from here or from the time-sliced PathQueue. `start` and `end` are the
  // snapped 3D points (with their heights), so string pulling works on ramps and stairs.
  dtPolyRef path[detail::kMaxPathPolys];
  int count = 0;
  dtStatus status = query.initSlicedFindPath(startRef, endRef, start, end, &filter, 0);
  while (dtStatusInProgress(status)) status = query.updateSlicedFindPath(1 << 30, nullptr);
  if (dtStatusFailed(status)) return PathStatus::Failed;
  status = query.finalizeSlicedFindPath(path, &count, detail::kMaxPathPolys);
  if (dtStatusFailed(status) || count == 0) return PathStatus::Failed;
  const bool partial = dtStatusDetail(status, DT_PARTIAL_RESULT) || path[count - 1] != endRef;
  return detail::straighten(query, start, end, path, count, partial, corners);
}

// The random point of randomPoint, with its fan-interpolated height and polygon.
struct RandomSample {
  Vec2 p;
  float height = 0.0f;
  dtPolyRef ref = 0;
};

std::optional<RandomSample> randomSample(const NavMesh& mesh, float r0, float r1, float r2) {
  const auto& areas = detail::data(mesh).areas;
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
  mesh.detour()->getTileAndPolyByRefUnsafe(it->ref, &tile, &poly);
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
  RandomSample out;
  out.p = Vec2{static_cast<float>(wa * v0[0] + wb * a[0] + wc * b[0]),
               static_cast<float>(wa * v0[2] + wb * a[2] + wc * b[2])};
  out.height = static_cast<float>(wa * v0[1] + wb * a[1] + wc * b[1]);
  out.ref = it->ref;
  return out;
}

}  // namespace

NavQuery::NavQuery(std::shared_ptr<const NavMesh> mesh, int maxNodes) : mesh_(std::move(mesh)) {
  query_ = dtAllocNavMeshQuery();
  query_->init(mesh_->detour(), std::clamp(maxNodes, 16, 65535));
  filter_ = new dtQueryFilter();
  filter_->setIncludeFlags(kWalkFlag);  // not a closed cut polygon (NavMesh::setClosed)
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

std::optional<MeshPoint> NavQuery::snap(Vec2 p, float height, float searchRadius) const {
  if (!mesh_->layered()) {
    const auto hit = nearest(p, searchRadius);
    if (!hit) return std::nullopt;
    return MeshPoint{hit->first, 0.0f, hit->second};
  }
  const float r = std::max(searchRadius, 0.0f);
  const float extents[3] = {r, kLevelSearch, r};
  float snapped[3];
  const dtPolyRef ref = detail::snapLevel(*query_, *filter_, p, height, extents, snapped);
  if (ref == 0) return std::nullopt;
  const Vec2 q = detail::fromRecast(snapped);
  if (lengthSq(q - p) > r * r) return std::nullopt;  // the search box's corners reach beyond r
  return MeshPoint{q, snapped[1], static_cast<PolyRef>(ref)};
}

float NavQuery::heightAt(PolyRef ref, Vec2 p) const {
  if (!mesh_->layered()) return 0.0f;
  const auto polyRef = static_cast<dtPolyRef>(ref);
  const dtMeshTile* tile = nullptr;
  const dtPoly* poly = nullptr;
  if (ref == 0 || dtStatusFailed(mesh_->detour()->getTileAndPolyByRef(polyRef, &tile, &poly))) return 0.0f;
  float pos[3];
  detail::toRecast(p, pos);
  float h = 0.0f;
  if (dtStatusSucceed(query_->getPolyHeight(polyRef, pos, &h))) return h;
  // p is off the polygon: the height of the closest point on its boundary.
  float mean = 0.0f;
  for (int k = 0; k < poly->vertCount; ++k) mean += tile->verts[poly->verts[k] * 3 + 1];
  pos[1] = poly->vertCount > 0 ? mean / static_cast<float>(poly->vertCount) : 0.0f;
  float closest[3];
  if (dtStatusSucceed(query_->closestPointOnPoly(polyRef, pos, closest, nullptr))) return closest[1];
  return pos[1];
}

PathStatus NavQuery::findPath(Vec2 from, Vec2 to, std::vector<Vec2>& corners) const {
  const detail::EndSearch ground;  // height 0, kSnapExtents
  return findPathFrom(*query_, *filter_, from, ground, to, ground, corners);
}

PathStatus NavQuery::findPath(Vec2 from, float fromHeight, Vec2 to, float toHeight,
                              std::vector<Vec2>& corners) const {
  return findPathFrom(*query_, *filter_, from, detail::endSearch(*mesh_, fromHeight), to,
                      detail::endSearch(*mesh_, toHeight), corners);
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
  // Heights 0: Detour's moveAlongSurface works in the ground plane along polygon links (the
  // result's height is interpolated from these and dropped), so this is right on any level.
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

bool NavQuery::reachable(Vec2 from, float fromHeight, Vec2 to, float toHeight) const {
  std::vector<Vec2> corners;
  return findPath(from, fromHeight, to, toHeight, corners) == PathStatus::Complete;
}

bool NavQuery::visible(Vec2 a, Vec2 b) const {
  float start[3];
  const dtPolyRef startRef = detail::snap(*query_, *filter_, a, detail::kSnapExtents, start);
  return startRef != 0 && detail::rayStaysOnMesh(*query_, *filter_, startRef, a, b, 0.0f);
}

bool NavQuery::visible(Vec2 a, float height, Vec2 b) const {
  if (!mesh_->layered()) return visible(a, b);
  const detail::EndSearch search = detail::endSearch(*mesh_, height);
  float start[3];
  const dtPolyRef startRef = detail::snapEnd(*query_, *filter_, a, search, start);
  return startRef != 0 && detail::rayStaysOnMesh(*query_, *filter_, startRef, a, b, start[1]);
}

std::optional<Vec2> NavQuery::randomPoint(float r0, float r1, float r2) const {
  const auto sample = randomSample(*mesh_, r0, r1, r2);
  if (!sample) return std::nullopt;
  return sample->p;
}

std::optional<MeshPoint> NavQuery::randomMeshPoint(float r0, float r1, float r2) const {
  const auto sample = randomSample(*mesh_, r0, r1, r2);
  if (!sample) return std::nullopt;
  MeshPoint out{sample->p, 0.0f, static_cast<PolyRef>(sample->ref)};
  if (mesh_->layered()) {
    // The detail mesh's height where the point lies; the fan's if Detour declines.
    float pos[3];
    detail::toRecast(sample->p, pos);
    float h = 0.0f;
    out.height = dtStatusSucceed(query_->getPolyHeight(sample->ref, pos, &h)) ? h : sample->height;
  }
  return out;
}

}  // namespace throng::nav

// throng::nav (private) — what a built NavMesh owns besides Detour's tiles: the area-weighted
// polygon table randomPoint draws from. The public NavMesh holds only a dtNavMesh*; the object
// behind it is a NavMeshData, so this table is built once with the mesh and shared read-only by
// every NavQuery (constructing a NavQuery stays cheap). Also the helpers shared by NavQuery and
// PathQueue, so a queued path is exactly the path NavQuery::findPath would return.
#pragma once
#include <DetourNavMesh.h>
#include <DetourNavMeshQuery.h>

#include <cstdint>
#include <vector>

#include "throng/nav/navmesh.hpp"

namespace throng::nav::detail {

/// One walkable polygon, in deterministic (tile index, polygon index) order.
struct AreaEntry {
  dtPolyRef ref = 0;
  double cumulativeArea = 0.0;  ///< sum of areas of this and all earlier polygons [m²]
};

struct NavMeshData : dtNavMesh {
  std::vector<AreaEntry> areas;  ///< cumulative areas, increasing; back().cumulativeArea = total
};

inline const NavMeshData& data(const NavMesh& mesh) {
  return *static_cast<const NavMeshData*>(mesh.detour());
}

/// Half extents used to snap path ends onto the mesh: 2 m horizontally, 1 m vertically.
inline constexpr float kSnapExtents[3] = {2.0f, 1.0f, 2.0f};
/// Longest polygon corridor a path may have; longer searches return Partial.
inline constexpr int kMaxPathPolys = 4096;
/// Most corners a straight path may have.
inline constexpr int kMaxStraightCorners = 1024;

inline void toRecast(Vec2 p, float out[3]) {
  out[0] = p.x;
  out[1] = 0.0f;
  out[2] = p.y;
}
/// Ground point p at height `height` (scenario z) in Recast's y-up order.
inline void toRecast(Vec2 p, float height, float out[3]) {
  out[0] = p.x;
  out[1] = height;
  out[2] = p.y;
}
inline Vec2 fromRecast(const float* v) { return {v[0], v[2]}; }

/// Where a height-hinted path end is searched for: the height itself and ±kLevelSearch on a
/// layered mesh; on a flat mesh the hint is ignored (height 0, kSnapExtents), as without one.
struct EndSearch {
  float height = 0.0f;
  float extents[3] = {kSnapExtents[0], kSnapExtents[1], kSnapExtents[2]};
  bool layered = false;  ///< snap with snapLevel (the height picks the floor)
};
inline EndSearch endSearch(const NavMesh& mesh, float height) {
  EndSearch s;
  if (mesh.layered()) {
    s.height = height;
    s.extents[1] = kLevelSearch;
    s.layered = true;
  }
  return s;
}

/// Nearest polygon to p within the half extents; 0 when none. `snapped` receives the point on it.
dtPolyRef snap(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, const float extents[3],
               float snapped[3]);
/// Layered meshes: the point nearest to (p, height) over every polygon in the box whose closest
/// point lies within ±extents[1] of `height` (Detour's findNearestPoly keeps a polygon whose
/// bounding box reaches into the band even when the polygon itself — a ramp with part of the floor
/// above — is far above or below it). Ties keep the first polygon in Detour's query order.
dtPolyRef snapLevel(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, float height,
                    const float extents[3], float snapped[3]);
/// snapLevel on a layered search, snap otherwise.
dtPolyRef snapEnd(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, const EndSearch& search,
                  float snapped[3]);
/// The same around (p, height).
dtPolyRef snap(const dtNavMeshQuery& query, const dtQueryFilter& filter, Vec2 p, float height,
               const float extents[3], float snapped[3]);

/// String-pulls a polygon corridor from `start` (on path[0]) toward `end` into corners (start
/// excluded). `partial` is whether the corridor failed to reach the target polygon. `heights`, when
/// given, gets each corner's height [m] (the floor it is on, on a layered mesh).
PathStatus straighten(const dtNavMeshQuery& query, const float start[3], const float end[3],
                      const dtPolyRef* path, int pathCount, bool partial, std::vector<Vec2>& corners,
                      std::vector<float>* heights = nullptr);

}  // namespace throng::nav::detail

// throng::nav::NavMesh — the walkable area as a Recast/Detour navigation mesh, eroded by the agent
// radius, tiled so that large worlds (hundreds of metres, 10^5..10^6 agents) fit. Built once when
// a World is built; read-only afterwards, so any number of NavQuery objects (one per thread) can
// query it at once.
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/core/result.hpp"

class dtNavMesh;
class dtNavMeshQuery;
class dtQueryFilter;

namespace throng::nav {

using core::Polygon;
using core::Vec2;

/// Detour polygon reference (opaque); 0 = none.
using PolyRef = std::uint64_t;

/// A region of the floor cut into polygons of its own (a door: an exit's disc or polygon), so that
/// closing it (NavMesh::setClosed) takes exactly its floor out of the walkable surface.
struct CutRegion {
  Vec2 centre;
  float radius = 0.0f;  ///< a disc of this radius around `centre` when `polygon` is empty [m]
  Polygon polygon;      ///< used when not empty
  float height = 0.0f;  ///< the floor it is on (layered meshes; within kLevelSearch) [m]
  /// Whether ground point p lies in the region, or within `margin` of it (in the plane; heights
  /// are the caller's).
  [[nodiscard]] bool contains(Vec2 p, float margin = 0.0f) const;
};

struct NavMeshConfig {
  float agentRadius = 0.2f;  ///< erosion radius [m] [Limit: >= 0]
  /// Regions whose floor becomes polygons of its own, flagged kCutFlag: the cells whose centre lies
  /// in the region or within kCutMargin cells of it (cells, and contour simplification by up to
  /// 1.1 cells, would otherwise leave the polygons' edge up to 1.6 cells inside the region; with
  /// the margin the whole region is covered, so a closed cut keeps every centre out of it).
  /// Polygons never straddle a cut's edge. Without cuts the mesh is as before.
  std::vector<CutRegion> cuts;
  // Terrain meshes only (NavMesh::buildFromTerrain): what a person can walk on and under.
  float maxSlopeDeg = 45.0f;  ///< steepest walkable triangle [deg] (ramps; stairs are climbed step by step)
  float maxClimb = 0.35f;     ///< highest step walked up or down [m]
  float clearance = 2.0f;     ///< headroom needed above a walkable surface [m]
  /// Ground steeper than this — its mean slope over kStairBaseline — is a stair: its polygons get
  /// the area kStairArea (slower walking, dearer routes). One rule for stairs and steep ramps: 15°
  /// lies above the steepest ramps building codes allow (1:12 ≈ 4.8°, 1:8 ≈ 7.1°) and below the
  /// shallowest stairs (riser 0.10 m on a 0.35 m tread ≈ 16°; common stairs 27°–37°) [deg] [Limit: (0, 90)]
  float stairSlopeDeg = 15.0f;
  float cellSize = 0.0f;     ///< voxel size [m]; 0 = max(agentRadius/4, sqrt(bounding area / 4e7)) clamped to [0.03, 0.3]
  float tileSize = 24.0f;    ///< tile edge [m] [Limit: > 4 * cellSize]. Smaller tiles mean smaller polygons and
                             ///< closer-to-shortest A* paths (300 m pillar field: mean path/straight ratio
                             ///< 1.026 at 24 m, 1.073 at 48 m) for ~10% more build time.
  /// When set, a build stops between tiles soon after `*cancel` becomes non-zero (a signal handler
  /// sets it: Ctrl-C during `throng check`) and fails with an "interrupted" diagnostic. Not owned.
  const std::atomic<int>* cancel = nullptr;
};

/// Detour polygon areas (dtPoly::getArea) of a terrain mesh: level ground and gentle ramps, and
/// stairs and steep ramps (NavMeshConfig::stairSlopeDeg). A flat mesh has floor only.
inline constexpr unsigned char kFloorArea = 0;
inline constexpr unsigned char kStairArea = 1;
/// Detour polygon flags: every open polygon has kWalkFlag, which every query filter of NavQuery and
/// PathQueue includes; polygons of a NavMeshConfig::cuts region also have kCutFlag. A closed cut
/// polygon (NavMesh::setClosed) has kCutFlag only: no query, path or move enters it.
inline constexpr unsigned short kWalkFlag = 1;
inline constexpr unsigned short kCutFlag = 2;
/// How far beyond a cut region its polygons reach, at most [cells] (NavMeshConfig::cuts).
inline constexpr float kCutMargin = 2.0f;
/// Horizontal length over which a stair's slope is measured [m]: long enough to span two treads
/// (0.25–0.35 m each), so a stair's flat treads and steep risers average to its pitch.
inline constexpr float kStairBaseline = 1.0f;

/// The ground of one navmesh polygon.
struct Surface {
  bool stair = false;  ///< area kStairArea
  /// The polygon's mean gradient: rise per horizontal metre along x and along y (dz/dx, dz/dy);
  /// its dot product with a walking direction is the slope walked (> 0 uphill). Zero on a flat mesh.
  Vec2 gradient;
};

/// A world's 3D walking geometry (multi-level worlds: floors joined by stairs or ramps). Scenario
/// coordinates: ground (x, y) and height z [m], z up. Triangles index `vertices` (3 per triangle,
/// any winding).
struct TerrainMesh {
  std::vector<float> vertices;           ///< x, y, z per vertex
  std::vector<std::uint32_t> walkable;   ///< triangles people walk on (floors, stairs, ramps)
  std::vector<std::uint32_t> obstacles;  ///< solid geometry: never walkable, blocks the floor it stands on
  [[nodiscard]] bool empty() const { return walkable.empty(); }
};

class NavMesh {
 public:
  /// Builds from walkable polygons (any winding) minus obstacle polygons. Fails with a
  /// diagnostic when nothing walkable remains after erosion. `source` names the input in diagnostics.
  static core::Result<std::shared_ptr<const NavMesh>> build(std::span<const Polygon> walkable,
                                                            std::span<const Polygon> obstacles,
                                                            const NavMeshConfig& config);
  /// Builds from 3D triangles with Recast (walkable slope, climb and clearance from `config`), so
  /// floors above each other, stairs and ramps become one connected navigation mesh. Obstacle
  /// triangles are rasterised as solid, unwalkable geometry. Fails with a diagnostic when nothing
  /// walkable remains.
  static core::Result<std::shared_ptr<const NavMesh>> buildFromTerrain(const TerrainMesh& terrain,
                                                                       const NavMeshConfig& config);
  ~NavMesh();
  NavMesh(const NavMesh&) = delete;
  NavMesh& operator=(const NavMesh&) = delete;

  [[nodiscard]] const dtNavMesh* detour() const { return mesh_; }
  [[nodiscard]] const NavMeshConfig& config() const { return config_; }
  /// About the narrowest opening between walls that stays walkable [m]: twice the erosion, which is
  /// the agent radius rounded up to whole cells plus one cell (build_common.hpp). Narrower doors close.
  [[nodiscard]] float narrowestOpening() const;
  [[nodiscard]] core::Aabb bounds() const { return bounds_; }
  /// True when built from a TerrainMesh: polygons have heights and may lie above each other, and
  /// queries need a height to pick the level. False: one flat level at height 0.
  [[nodiscard]] bool layered() const { return layered_; }
  /// Lowest and highest walkable height [m] (0, 0 for a flat mesh).
  [[nodiscard]] float minHeight() const { return minHeight_; }
  [[nodiscard]] float maxHeight() const { return maxHeight_; }
  [[nodiscard]] std::size_t polygonCount() const;
  /// Outline of every polygon (for viewers and debugging), in the plane.
  [[nodiscard]] std::vector<Polygon> polygons() const;
  /// The walls: outer edges of the polygons (edges with no neighbouring polygon and no cross-tile
  /// link), in the plane. `heights`, when given, receives the height at both ends of each edge
  /// (two values per edge, in order). The mesh is eroded by the body radius, so these bound agent
  /// centres.
  [[nodiscard]] std::vector<core::Segment> boundary(std::vector<float>* heights = nullptr) const;
  /// The ground of polygon `ref`: its area and its mean gradient (from its detail triangles).
  /// A stale or null reference gives flat floor.
  [[nodiscard]] Surface surface(PolyRef ref) const;

  /// A copy with the same polygons and references, whose flags the owner may change (setClosed)
  /// without touching the meshes other worlds share.
  [[nodiscard]] std::shared_ptr<NavMesh> clone() const;
  /// The polygons of a cut region (kCutFlag) whose centroid lies in `region` or within kCutMargin
  /// cells of it (on a layered mesh:
  /// whose height at the centroid is within kLevelSearch of region.height), in reference order.
  [[nodiscard]] std::vector<PolyRef> cutPolygons(const CutRegion& region) const;
  /// Whether some ground polygon overlaps `region` (on a layered mesh: one whose mean height is
  /// within kLevelSearch of region.height): cutting the region would give it polygons of its own.
  [[nodiscard]] bool floorIn(const CutRegion& region) const;
  /// Closes (kCutFlag only: nothing enters them) or opens (kWalkFlag | kCutFlag) polygons of
  /// cutPolygons(). Not thread-safe: call between queries (queries of other threads must not run).
  void setClosed(std::span<const PolyRef> polys, bool closed);

 private:
  NavMesh() = default;
  dtNavMesh* mesh_ = nullptr;
  NavMeshConfig config_;
  core::Aabb bounds_;
  bool layered_ = false;
  float minHeight_ = 0.0f, maxHeight_ = 0.0f;
};

/// A point on the mesh: ground position, its height on the polygon, the polygon.
struct MeshPoint {
  Vec2 p;
  float height = 0.0f;
  PolyRef ref = 0;
};

/// Vertical half-extent of a height-hinted search on a layered mesh [m]: floors closer than about
/// twice this need accurate hints.
inline constexpr float kLevelSearch = 1.5f;

enum class PathStatus : std::uint8_t {
  Complete,  ///< the path reaches the target
  Partial,   ///< target unreachable: the path ends at the closest reachable point (an answer, not a failure)
  Failed,    ///< start not on the mesh
};

/// Queries on one NavMesh. Not thread-safe: use one per thread. Results are a pure function of the
/// inputs, so which thread's query answers never changes a trajectory.
class NavQuery {
 public:
  explicit NavQuery(std::shared_ptr<const NavMesh> mesh, int maxNodes = 4096);
  ~NavQuery();
  NavQuery(const NavQuery&) = delete;
  NavQuery& operator=(const NavQuery&) = delete;

  /// Nearest point on the mesh within `searchRadius` metres of p (horizontal), if any.
  [[nodiscard]] std::optional<std::pair<Vec2, PolyRef>> nearest(Vec2 p, float searchRadius = 2.0f) const;

  /// Nearest point on the mesh within `searchRadius` metres (horizontal) of p at about `height`: on
  /// a layered mesh the polygon nearest in 3D within ±kLevelSearch of `height` (so the hint picks
  /// the floor); on a flat mesh the same as nearest(p, searchRadius), with height 0.
  [[nodiscard]] std::optional<MeshPoint> snap(Vec2 p, float height, float searchRadius = 2.0f) const;

  /// Height [m] of the mesh at ground point p on polygon `ref` (p inside or near it); 0 on a flat mesh.
  [[nodiscard]] float heightAt(PolyRef ref, Vec2 p) const;

  /// String-pulled path from `from` to `to`: `corners` receives the turning points after `from`,
  /// ending with the (possibly clamped) target. Heights pick the levels on a layered mesh.
  PathStatus findPath(Vec2 from, Vec2 to, std::vector<Vec2>& corners) const;
  PathStatus findPath(Vec2 from, float fromHeight, Vec2 to, float toHeight, std::vector<Vec2>& corners) const;

  /// Moves from `from` (on polygon `ref`) toward `to`, sliding along the mesh boundary (Detour's
  /// moveAlongSurface); returns the reached point and updates `ref`. Keeps agents inside the mesh.
  Vec2 moveAlongSurface(Vec2 from, Vec2 to, PolyRef& ref) const;

  /// Whether `to` is reachable from `from` (both snapped within 2 m).
  [[nodiscard]] bool reachable(Vec2 from, Vec2 to) const;
  [[nodiscard]] bool reachable(Vec2 from, float fromHeight, Vec2 to, float toHeight) const;

  /// True when the straight segment a→b stays on the mesh (Detour raycast).
  [[nodiscard]] bool visible(Vec2 a, Vec2 b) const;
  /// The same from `a` at about `height` (the level it starts on).
  [[nodiscard]] bool visible(Vec2 a, float height, Vec2 b) const;

  /// Uniformly random point on the mesh (area-weighted), drawn from `r01` values in [0,1):
  /// deterministic for given inputs.
  [[nodiscard]] std::optional<Vec2> randomPoint(float r0, float r1, float r2) const;
  /// The same point with its height and polygon.
  [[nodiscard]] std::optional<MeshPoint> randomMeshPoint(float r0, float r1, float r2) const;

  [[nodiscard]] const NavMesh& mesh() const { return *mesh_; }

 private:
  std::shared_ptr<const NavMesh> mesh_;
  dtNavMeshQuery* query_ = nullptr;
  dtQueryFilter* filter_ = nullptr;
};

}  // namespace throng::nav

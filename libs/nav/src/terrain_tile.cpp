// throng::nav (private) — one tile of the 3D terrain pipeline; see terrain_tile.hpp.
#include "terrain_tile.hpp"

#include <DetourAlloc.h>
#include <DetourNavMeshBuilder.h>
#include <Recast.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>

#include "recast_context.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav::detail {
namespace {

// Detail mesh sampling: every 6 cells, to within one cell height. (A sample distance of 0 crashes
// Debian's 2021 Recast snapshot; see tile_builder.cpp.)
constexpr float kDetailSampleCells = 6.0f;
constexpr float kDetailMaxErrorCells = 1.0f;

// Compact-heightfield area of stair spans (walkable, not RC_WALKABLE_AREA); polygons of it become
// kStairArea in the Detour tile.
constexpr unsigned char kStairSpanArea = 1;

/// The span reached from span `i` at cell (x, y) after up to `steps` connected moves in direction
/// `dir` (rcGetDirOffsetX/Y), and how many moves it made (fewer at the edge of the walkable area).
std::pair<int, int> walkSpans(const rcCompactHeightfield& chf, int x, int y, int i, int dir, int steps) {
  int moved = 0;
  for (; moved < steps; ++moved) {
    const rcCompactSpan& s = chf.spans[i];
    const int con = rcGetCon(s, dir);
    if (con == RC_NOT_CONNECTED) break;
    x += rcGetDirOffsetX(dir);
    y += rcGetDirOffsetY(dir);
    i = static_cast<int>(chf.cells[x + y * chf.width].index) + con;
  }
  return {i, moved};
}

/// Marks as stair area every walkable span whose ground, measured over kStairBaseline centred on
/// it (central differences along x and along y, over connected spans: the same floor), rises
/// steeper than `slopeDeg`; then a median filter removes single-span specks, so stairs and floors
/// become whole regions (Recast never merges regions of different areas) and so whole polygons.
bool markStairs(rcContext& ctx, rcCompactHeightfield& chf, float slopeDeg) {
  const int half = std::max(1, static_cast<int>(std::lround(0.5f * kStairBaseline / chf.cs)));
  const float limit = std::tan(slopeDeg * std::numbers::pi_v<float> / 180.0f);
  const float limit2 = limit * limit;
  for (int y = 0; y < chf.height; ++y) {
    for (int x = 0; x < chf.width; ++x) {
      const rcCompactCell& c = chf.cells[x + y * chf.width];
      for (int i = static_cast<int>(c.index), end = static_cast<int>(c.index + c.count); i < end; ++i) {
        if (chf.areas[i] == RC_NULL_AREA) continue;
        float g2 = 0.0f;
        for (int axis = 0; axis < 2; ++axis) {  // directions 2/0: +x/−x; 1/3: +y/−y (Recast z)
          const auto [ahead, na] = walkSpans(chf, x, y, i, axis == 0 ? 2 : 1, half);
          const auto [behind, nb] = walkSpans(chf, x, y, i, axis == 0 ? 0 : 3, half);
          if (na + nb == 0) continue;
          const float rise = static_cast<float>(static_cast<int>(chf.spans[ahead].y) - static_cast<int>(chf.spans[behind].y)) * chf.ch;
          const float g = rise / (static_cast<float>(na + nb) * chf.cs);
          g2 += g * g;
        }
        if (g2 > limit2) chf.areas[i] = kStairSpanArea;
      }
    }
  }
  return rcMedianFilterWalkableArea(&ctx, chf);
}

// Gathers the listed triangles (3 indices each) of `all` into one index array.
std::vector<int> gather(const std::vector<int>& all, std::span<const int> which) {
  std::vector<int> out;
  out.reserve(which.size() * 3);
  for (const int t : which) {
    const auto base = static_cast<std::size_t>(t) * 3;
    out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(base),
               all.begin() + static_cast<std::ptrdiff_t>(base + 3));
  }
  return out;
}

/// One terrain tile going through the Recast pipeline: each step keeps what the next needs and
/// returns nullptr, or what failed.
class TerrainTileBuilder {
 public:
  TerrainTileBuilder(const TerrainSettings& settings, int tileX, int tileY)
      : settings_(settings), s_(settings.tile), tileX_(tileX), tileY_(tileY) {}

  /// The heightfield of the tile and its border: walkable triangles (slope-limited), then
  /// obstacles (solid), ledges and low headroom filtered out.
  const char* rasterize(const TerrainInput& input, std::span<const int> walkableTris, std::span<const int> obstacleTris) {
    const float cs = s_.cellSize;
    const int size = s_.tileCells + 2 * s_.borderCells;
    const float tileWidth = static_cast<float>(s_.tileCells) * cs;
    const float minX = s_.originX + static_cast<float>(tileX_) * tileWidth - static_cast<float>(s_.borderCells) * cs;
    const float minY = s_.originY + static_cast<float>(tileY_) * tileWidth - static_cast<float>(s_.borderCells) * cs;
    const float bmin[3] = {minX, settings_.minY, minY};
    const float bmax[3] = {minX + static_cast<float>(size) * cs, settings_.maxY, minY + static_cast<float>(size) * cs};
    const int climb = settings_.walkableClimbCells;
    const int height = settings_.walkableHeightCells;

    hf_.reset(rcAllocHeightfield());
    if (!hf_ || !rcCreateHeightfield(&ctx_, *hf_, size, size, bmin, bmax, cs, settings_.cellHeight))
      return "could not allocate the heightfield";
    const int nv = static_cast<int>(input.verts.size() / 3);

    // Walkable triangles first, then obstacles: a merged span takes the area of the span added last
    // when their tops differ by more than the merge threshold, and obstacles merge with threshold
    // -1, so whatever an obstacle overlaps becomes solid (never the other way round).
    const std::vector<int> walk = gather(input.walkable, walkableTris);
    const int nw = static_cast<int>(walk.size() / 3);
    std::vector<unsigned char> areas(static_cast<std::size_t>(nw), RC_NULL_AREA);
    rcMarkWalkableTriangles(&ctx_, settings_.maxSlopeDeg, input.verts.data(), nv, walk.data(), nw, areas.data());
    if (!rcRasterizeTriangles(&ctx_, input.verts.data(), nv, walk.data(), areas.data(), nw, *hf_, climb))
      return "could not rasterise the walkable triangles";
    if (!obstacleTris.empty()) {
      const std::vector<int> obs = gather(input.obstacles, obstacleTris);
      const int no = static_cast<int>(obs.size() / 3);
      const std::vector<unsigned char> solid(static_cast<std::size_t>(no), RC_NULL_AREA);
      if (!rcRasterizeTriangles(&ctx_, input.verts.data(), nv, obs.data(), solid.data(), no, *hf_, -1))
        return "could not rasterise the obstacle triangles";
    }
    // No rcFilterLowHangingWalkableObstacles: it would make low obstacles walkable.
    rcFilterLedgeSpans(&ctx_, height, climb, *hf_);
    rcFilterWalkableLowHeightSpans(&ctx_, height, *hf_);
    return nullptr;
  }

  /// The compact heightfield, its stairs marked, eroded by the agent radius and partitioned into
  /// regions.
  const char* buildRegions() {
    const float cs = s_.cellSize;
    chf_.reset(rcAllocCompactHeightfield());
    if (!chf_ || !rcBuildCompactHeightfield(&ctx_, settings_.walkableHeightCells, settings_.walkableClimbCells, *hf_, *chf_))
      return "could not build the compact heightfield";
    hf_.reset();
    if (!markStairs(ctx_, *chf_, settings_.stairSlopeDeg)) return "could not mark the stairs";
    if (s_.radiusCells > 0 && !rcErodeWalkableArea(&ctx_, s_.radiusCells, *chf_)) return "could not erode the walkable area";
    markCuts(*chf_, s_);
    // Monotone partitioning as in the flat build (see tile_builder.cpp); it handles spans above
    // each other through the compact heightfield's neighbour links.
    const int minRegion = static_cast<int>(std::ceil(kMinIslandArea / (cs * cs)));
    const int mergeRegion = static_cast<int>(std::ceil(kMergeRegionArea / (cs * cs)));
    if (!rcBuildRegionsMonotone(&ctx_, *chf_, s_.borderCells, minRegion, mergeRegion))
      return "could not partition the walkable area into regions";
    return nullptr;
  }

  /// Contours, the polygon mesh and the detail mesh (the polygons' heights inside: ramps meeting
  /// floors, stairs). Leaves empty() true when the tile has no polygon.
  const char* buildPolygons() {
    const float cs = s_.cellSize;
    std::unique_ptr<rcContourSet, ContourDeleter> cset(rcAllocContourSet());
    const int maxEdgeCells = static_cast<int>(kMaxEdgeLength / cs);
    if (!cset || !rcBuildContours(&ctx_, *chf_, kMaxEdgeError, maxEdgeCells, *cset)) return "could not trace contours";
    if (cset->nconts == 0) return nullptr;
    pmesh_.reset(rcAllocPolyMesh());
    if (!pmesh_ || !rcBuildPolyMesh(&ctx_, *cset, kMaxVertsPerPoly, *pmesh_)) return "could not build the polygon mesh";
    if (pmesh_->npolys == 0) return nullptr;
    if (pmesh_->nverts >= 0xffff) return "the tile has more than 65534 vertices; use a smaller tileSize";
    // Heights and nearest-polygon searches then follow the surface rather than a fan of the
    // outline's vertices.
    dmesh_.reset(rcAllocPolyMeshDetail());
    if (!dmesh_ || !rcBuildPolyMeshDetail(&ctx_, *pmesh_, *chf_, kDetailSampleCells * cs,
                                          kDetailMaxErrorCells * settings_.cellHeight, *dmesh_))
      return "could not build the detail mesh";
    chf_.reset();
    return nullptr;
  }

  [[nodiscard]] bool empty() const { return !dmesh_; }

  /// The meshes lowered by half a cell and packed as Detour tile data.
  TileOutput pack() {
    const float ch = settings_.cellHeight;
    // Voxels round surfaces up to the next cell top (0 to 1 cell too high; the heightfield starts
    // half a cell below a whole-cell boundary, so that is 0.5 cell on average): lower the tile by
    // half a cell so heights are within half a cell of the geometry.
    const float lift = 0.5f * ch;
    for (int i = 0; i < dmesh_->nverts; ++i) dmesh_->verts[i * 3 + 1] -= lift;

    for (int i = 0; i < pmesh_->npolys; ++i) {
      // Walkable (passes the default query filter); a cut region's polygons are marked as such.
      pmesh_->flags[i] = isCutArea(pmesh_->areas[i]) ? (kWalkFlag | kCutFlag) : kWalkFlag;
      pmesh_->areas[i] = pmesh_->areas[i] == kStairSpanArea ? kStairArea : kFloorArea;
    }
    dtNavMeshCreateParams params{};
    params.verts = pmesh_->verts;
    params.vertCount = pmesh_->nverts;
    params.polys = pmesh_->polys;
    params.polyAreas = pmesh_->areas;
    params.polyFlags = pmesh_->flags;
    params.polyCount = pmesh_->npolys;
    params.nvp = pmesh_->nvp;
    params.detailMeshes = dmesh_->meshes;
    params.detailVerts = dmesh_->verts;
    params.detailVertsCount = dmesh_->nverts;
    params.detailTris = dmesh_->tris;
    params.detailTriCount = dmesh_->ntris;
    params.tileX = tileX_;
    params.tileY = tileY_;
    params.tileLayer = 0;
    for (int k = 0; k < 3; ++k) {
      params.bmin[k] = pmesh_->bmin[k];
      params.bmax[k] = pmesh_->bmax[k];
    }
    params.bmin[1] -= lift;  // poly vertices are stored relative to bmin
    params.bmax[1] -= lift;
    params.walkableHeight = static_cast<float>(settings_.walkableHeightCells) * ch;
    params.walkableRadius = s_.agentRadius;
    params.walkableClimb = static_cast<float>(settings_.walkableClimbCells) * ch;
    params.cs = s_.cellSize;
    params.ch = ch;
    params.buildBvTree = true;

    TileOutput out;
    if (!dtCreateNavMeshData(&params, &out.data, &out.size)) return fail("could not pack the Detour tile data");
    out.polyCount = pmesh_->npolys;
    return out;
  }

  [[nodiscard]] TileOutput fail(const char* what) const { return detail::fail(what, ctx_); }

 private:
  const TerrainSettings& settings_;
  const TileSettings& s_;
  const int tileX_, tileY_;
  CollectingContext ctx_;
  std::unique_ptr<rcHeightfield, HeightfieldDeleter> hf_;
  std::unique_ptr<rcCompactHeightfield, CompactDeleter> chf_;
  std::unique_ptr<rcPolyMesh, PolyMeshDeleter> pmesh_;
  std::unique_ptr<rcPolyMeshDetail, DetailDeleter> dmesh_;
};

}  // namespace

TileOutput buildTerrainTile(const TerrainSettings& settings, int tileX, int tileY, const TerrainInput& input,
                            std::span<const int> walkableTris, std::span<const int> obstacleTris) {
  if (walkableTris.empty()) return {};
  TerrainTileBuilder tile(settings, tileX, tileY);
  if (const char* e = tile.rasterize(input, walkableTris, obstacleTris)) return tile.fail(e);
  if (const char* e = tile.buildRegions()) return tile.fail(e);
  if (const char* e = tile.buildPolygons()) return tile.fail(e);
  if (tile.empty()) return {};
  return tile.pack();
}

}  // namespace throng::nav::detail

// throng::nav (private) — one tile of the 3D terrain pipeline; see terrain_tile.hpp.
#include "terrain_tile.hpp"

#include <DetourAlloc.h>
#include <DetourNavMeshBuilder.h>
#include <Recast.h>

#include <cmath>
#include <memory>

#include "recast_context.hpp"

namespace throng::nav::detail {
namespace {

// Detail mesh sampling: every 6 cells, to within one cell height. (A sample distance of 0 crashes
// Debian's 2021 Recast snapshot; see tile_builder.cpp.)
constexpr float kDetailSampleCells = 6.0f;
constexpr float kDetailMaxErrorCells = 1.0f;

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

}  // namespace

TileOutput buildTerrainTile(const TerrainSettings& settings, int tileX, int tileY, const TerrainInput& input,
                            std::span<const int> walkableTris, std::span<const int> obstacleTris) {
  if (walkableTris.empty()) return {};
  CollectingContext ctx;
  const TileSettings& s = settings.tile;
  const float cs = s.cellSize;
  const float ch = settings.cellHeight;
  const int size = s.tileCells + 2 * s.borderCells;
  const float tileWidth = static_cast<float>(s.tileCells) * cs;
  const float minX = s.originX + static_cast<float>(tileX) * tileWidth - static_cast<float>(s.borderCells) * cs;
  const float minY = s.originY + static_cast<float>(tileY) * tileWidth - static_cast<float>(s.borderCells) * cs;
  const float bmin[3] = {minX, settings.minY, minY};
  const float bmax[3] = {minX + static_cast<float>(size) * cs, settings.maxY, minY + static_cast<float>(size) * cs};
  const int climb = settings.walkableClimbCells;
  const int height = settings.walkableHeightCells;

  std::unique_ptr<rcHeightfield, HeightfieldDeleter> hf(rcAllocHeightfield());
  if (!hf || !rcCreateHeightfield(&ctx, *hf, size, size, bmin, bmax, cs, ch))
    return fail("could not allocate the heightfield", ctx);
  const int nv = static_cast<int>(input.verts.size() / 3);

  // Walkable triangles first, then obstacles: a merged span takes the area of the span added last
  // when their tops differ by more than the merge threshold, and obstacles merge with threshold
  // -1, so whatever an obstacle overlaps becomes solid (never the other way round).
  const std::vector<int> walk = gather(input.walkable, walkableTris);
  const int nw = static_cast<int>(walk.size() / 3);
  std::vector<unsigned char> areas(static_cast<std::size_t>(nw), RC_NULL_AREA);
  rcMarkWalkableTriangles(&ctx, settings.maxSlopeDeg, input.verts.data(), nv, walk.data(), nw, areas.data());
  if (!rcRasterizeTriangles(&ctx, input.verts.data(), nv, walk.data(), areas.data(), nw, *hf, climb))
    return fail("could not rasterise the walkable triangles", ctx);
  if (!obstacleTris.empty()) {
    const std::vector<int> obs = gather(input.obstacles, obstacleTris);
    const int no = static_cast<int>(obs.size() / 3);
    const std::vector<unsigned char> solid(static_cast<std::size_t>(no), RC_NULL_AREA);
    if (!rcRasterizeTriangles(&ctx, input.verts.data(), nv, obs.data(), solid.data(), no, *hf, -1))
      return fail("could not rasterise the obstacle triangles", ctx);
  }
  // No rcFilterLowHangingWalkableObstacles: it would make low obstacles walkable.
  rcFilterLedgeSpans(&ctx, height, climb, *hf);
  rcFilterWalkableLowHeightSpans(&ctx, height, *hf);

  std::unique_ptr<rcCompactHeightfield, CompactDeleter> chf(rcAllocCompactHeightfield());
  if (!chf || !rcBuildCompactHeightfield(&ctx, height, climb, *hf, *chf))
    return fail("could not build the compact heightfield", ctx);
  hf.reset();
  if (s.radiusCells > 0 && !rcErodeWalkableArea(&ctx, s.radiusCells, *chf))
    return fail("could not erode the walkable area", ctx);
  // Monotone partitioning as in the flat build (see tile_builder.cpp); it handles spans above
  // each other through the compact heightfield's neighbour links.
  const int minRegion = static_cast<int>(std::ceil(kMinIslandArea / (cs * cs)));
  const int mergeRegion = static_cast<int>(std::ceil(kMergeRegionArea / (cs * cs)));
  if (!rcBuildRegionsMonotone(&ctx, *chf, s.borderCells, minRegion, mergeRegion))
    return fail("could not partition the walkable area into regions", ctx);

  std::unique_ptr<rcContourSet, ContourDeleter> cset(rcAllocContourSet());
  const int maxEdgeCells = static_cast<int>(kMaxEdgeLength / cs);
  if (!cset || !rcBuildContours(&ctx, *chf, kMaxEdgeError, maxEdgeCells, *cset))
    return fail("could not trace contours", ctx);
  if (cset->nconts == 0) return {};
  std::unique_ptr<rcPolyMesh, PolyMeshDeleter> pmesh(rcAllocPolyMesh());
  if (!pmesh || !rcBuildPolyMesh(&ctx, *cset, kMaxVertsPerPoly, *pmesh))
    return fail("could not build the polygon mesh", ctx);
  if (pmesh->npolys == 0) return {};
  if (pmesh->nverts >= 0xffff) return fail("the tile has more than 65534 vertices; use a smaller tileSize", ctx);
  // Detail mesh: the polygons' heights inside (ramps meeting floors, stairs), so heights and
  // nearest-polygon searches follow the surface rather than a fan of the outline's vertices.
  std::unique_ptr<rcPolyMeshDetail, DetailDeleter> dmesh(rcAllocPolyMeshDetail());
  if (!dmesh ||
      !rcBuildPolyMeshDetail(&ctx, *pmesh, *chf, kDetailSampleCells * cs, kDetailMaxErrorCells * ch, *dmesh))
    return fail("could not build the detail mesh", ctx);
  chf.reset();

  // Voxels round surfaces up to the next cell top (0 to 1 cell too high; the heightfield starts
  // half a cell below a whole-cell boundary, so that is 0.5 cell on average): lower the tile by
  // half a cell so heights are within half a cell of the geometry.
  const float lift = 0.5f * ch;
  for (int i = 0; i < dmesh->nverts; ++i) dmesh->verts[i * 3 + 1] -= lift;

  for (int i = 0; i < pmesh->npolys; ++i) {
    pmesh->flags[i] = 1;  // walkable: passes the default query filter
    pmesh->areas[i] = 0;
  }
  dtNavMeshCreateParams params{};
  params.verts = pmesh->verts;
  params.vertCount = pmesh->nverts;
  params.polys = pmesh->polys;
  params.polyAreas = pmesh->areas;
  params.polyFlags = pmesh->flags;
  params.polyCount = pmesh->npolys;
  params.nvp = pmesh->nvp;
  params.detailMeshes = dmesh->meshes;
  params.detailVerts = dmesh->verts;
  params.detailVertsCount = dmesh->nverts;
  params.detailTris = dmesh->tris;
  params.detailTriCount = dmesh->ntris;
  params.tileX = tileX;
  params.tileY = tileY;
  params.tileLayer = 0;
  for (int k = 0; k < 3; ++k) {
    params.bmin[k] = pmesh->bmin[k];
    params.bmax[k] = pmesh->bmax[k];
  }
  params.bmin[1] -= lift;  // poly vertices are stored relative to bmin
  params.bmax[1] -= lift;
  params.walkableHeight = static_cast<float>(height) * ch;
  params.walkableRadius = s.agentRadius;
  params.walkableClimb = static_cast<float>(climb) * ch;
  params.cs = cs;
  params.ch = ch;
  params.buildBvTree = true;

  TileOutput out;
  if (!dtCreateNavMeshData(&params, &out.data, &out.size)) return fail("could not pack the Detour tile data", ctx);
  out.polyCount = pmesh->npolys;
  return out;
}

}  // namespace throng::nav::detail

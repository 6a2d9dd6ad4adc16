// throng::nav (private) — builds one Detour tile of the flat floor: rasterize the walkable cells
// (walkable_raster), erode by the agent radius, partition into regions, trace contours, build the
// polygon mesh, and pack them with dtCreateNavMeshData. Reads polygons; writes the
// tile's Detour data. Tiles are independent, so they build in parallel.
#pragma once
#include <string>
#include <vector>

#include "throng/nav/navmesh.hpp"
#include "walkable_raster.hpp"

struct rcCompactHeightfield;

namespace throng::nav::detail {

struct TileSettings {
  float originX = 0;    ///< world x of tile (0,0)'s lower corner [m]
  float originY = 0;    ///< world y of tile (0,0)'s lower corner [m]
  float cellSize = 0;   ///< [m]
  int tileCells = 0;    ///< tile edge [cells]
  int borderCells = 0;  ///< extra cells rasterized around a tile so erosion sees its neighbours
  int radiusCells = 0;  ///< erosion [cells]
  float agentRadius = 0;
  const std::vector<CutRegion>* cuts = nullptr;  ///< NavMeshConfig::cuts (not owned)
  bool layered = false;                          ///< cuts match span heights (terrain builds)
};

/// Compact-heightfield areas of cut regions: region k's spans get kCutSpanArea + k % kCutSpanAreas
/// (so neighbouring regions stay apart); Recast never merges regions of different areas, so each
/// cut becomes polygons of its own. Stair spans use area 1 (terrain_tile.cpp).
inline constexpr unsigned char kCutSpanArea = 2;
inline constexpr int kCutSpanAreas = 32;
/// Whether a polygon of compact-heightfield area `area` lies in a cut region (not plain floor,
/// RC_WALKABLE_AREA, nor a stair).
inline constexpr bool isCutArea(unsigned char area) { return area >= kCutSpanArea && area < kCutSpanArea + kCutSpanAreas; }

/// Gives every walkable span of `chf` whose cell centre lies in one of `s.cuts` (on a layered build:
/// whose floor is within kLevelSearch of the region's height) its cut area. After erosion, so the
/// cuts do not change where the floor ends.
void markCuts(rcCompactHeightfield& chf, const TileSettings& s);

/// A built tile. `data` is allocated with dtAlloc; whoever takes it frees it (or hands it to
/// dtNavMesh::addTile with DT_TILE_FREE_DATA).
struct TileOutput {
  unsigned char* data = nullptr;
  int size = 0;
  int polyCount = 0;
  std::string error;  ///< non-empty when Recast or Detour failed
};

TileOutput buildTile(const TileSettings& settings, int tileX, int tileY,
                     const std::vector<RasterPolygon>& walkable, const std::vector<RasterPolygon>& obstacles);

}  // namespace throng::nav::detail

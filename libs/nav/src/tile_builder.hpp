// throng::nav (private) — builds one Detour tile of the flat floor: rasterize the walkable cells
// (walkable_raster), erode by the agent radius, partition into regions, trace contours, build the
// polygon mesh, and pack them with dtCreateNavMeshData. Reads polygons; writes the
// tile's Detour data. Tiles are independent, so they build in parallel.
#pragma once
#include <string>
#include <vector>

#include "walkable_raster.hpp"

namespace throng::nav::detail {

struct TileSettings {
  float originX = 0;    ///< world x of tile (0,0)'s lower corner [m]
  float originY = 0;    ///< world y of tile (0,0)'s lower corner [m]
  float cellSize = 0;   ///< [m]
  int tileCells = 0;    ///< tile edge [cells]
  int borderCells = 0;  ///< extra cells rasterized around a tile so erosion sees its neighbours
  int radiusCells = 0;  ///< erosion [cells]
  float agentRadius = 0;
};

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

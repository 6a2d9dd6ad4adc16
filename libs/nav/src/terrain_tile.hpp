// throng::nav (private) — builds one Detour tile of a 3D terrain (NavMesh::buildFromTerrain) with
// the full Recast voxel pipeline: rasterise the walkable triangles (slope-limited) and the obstacle
// triangles (solid, never walkable), filter ledges and low headroom, mark stairs (ground steeper than
// stairSlopeDeg: area kStairArea), erode by the agent radius,
// partition into regions, trace contours, build the polygon and detail meshes, pack them with
// dtCreateNavMeshData. Reads the prepared triangles; writes the tile's Detour data. Tiles are
// independent, so they build in parallel.
#pragma once
#include <span>
#include <vector>

#include "tile_builder.hpp"

namespace throng::nav::detail {

/// The terrain in Recast's y-up order, prepared once per build.
struct TerrainInput {
  std::vector<float> verts;   ///< x, height, y per vertex [m]
  std::vector<int> walkable;  ///< 3 vertex indices per triangle, wound so the normal points up (+y)
  std::vector<int> obstacles; ///< 3 vertex indices per triangle
};

struct TerrainSettings {
  TileSettings tile;           ///< grid, cell size, border and erosion, as the flat build
  float cellHeight = 0.1f;     ///< [m]
  float minY = 0, maxY = 0;    ///< heightfield range (Recast y) [m]
  float maxSlopeDeg = 45.0f;   ///< steepest walkable triangle [deg]
  float stairSlopeDeg = 15.0f; ///< ground steeper than this (over kStairBaseline) is stair area [deg]
  int walkableHeightCells = 0; ///< headroom [cells of cellHeight]
  int walkableClimbCells = 0;  ///< step height [cells of cellHeight]
};

/// Builds tile (tileX, tileY) from the walkable and obstacle triangles (indices into `input`'s
/// triangle lists, ascending) that may overlap it. No polygons: a TileOutput without data.
TileOutput buildTerrainTile(const TerrainSettings& settings, int tileX, int tileY, const TerrainInput& input,
                            std::span<const int> walkableTris, std::span<const int> obstacleTris);

}  // namespace throng::nav::detail

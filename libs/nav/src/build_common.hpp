// throng::nav (private) — what NavMesh::build (flat polygons) and NavMesh::buildFromTerrain (3D
// triangles) share: diagnostics helpers, Detour's reference-bit limits, and the assembly of built
// tiles into one dtNavMesh plus its area table for randomPoint. Reads built tiles; writes the mesh.
#pragma once
#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "navmesh_data.hpp"
#include "throng/core/result.hpp"
#include "tile_builder.hpp"

namespace throng::nav::detail {

inline constexpr const char* kSource = "navmesh";
// Detour packs tile index, polygon index and a salt into a dtPolyRef; the salt needs >= 10 bits.
inline constexpr int kRefBits = static_cast<int>(sizeof(dtPolyRef) * 8);
inline constexpr int kMinSaltBits = 10;

/// Whether a build was asked to stop (NavMeshConfig::cancel).
inline bool cancelled(const std::atomic<int>* cancel) {
  return cancel != nullptr && cancel->load(std::memory_order_relaxed) != 0;
}

inline core::Diagnostic diag(std::string pointer, std::string what, std::string expected, std::string hint = {}) {
  core::Diagnostic d;
  d.source = kSource;
  d.pointer = std::move(pointer);
  d.what = std::move(what);
  d.expected = std::move(expected);
  d.hint = std::move(hint);
  return d;
}

inline std::string metres(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g m", static_cast<double>(v));
  return buf;
}

inline int ilog2Ceil(unsigned v) {
  int bits = 0;
  while ((1u << bits) < v) ++bits;
  return bits;
}

/// Cells the walkable area is eroded by for agents of radius r on cells of size cs: one cell more
/// than the radius — cells count as walkable when their centre is, and contour simplification moves
/// edges up to ~1 cell, so eroding by ceil(r / cs) alone lets the mesh reach up to ~1.5 cells closer
/// than r to a wall (measured: 0.1 m into obstacles at cs = r = 0.2 m). With the extra cell the mesh
/// keeps >= ~r/2 from every wall at cs = r/2 (and >= r from straight walls); a doorway then needs to
/// be wider than about 2 * (r + cs) to stay open. A diagnostic when that is 250 cells or more.
inline core::Result<int> erosionCells(float agentRadius, float cs) {
  const int cells = agentRadius > 0.0f ? static_cast<int>(std::ceil(agentRadius / cs - 1e-4f)) + 1 : 0;
  if (cells >= 250) {
    return diag("/agentRadius", "agent radius " + metres(agentRadius) + " is " + std::to_string(cells) +
                                    " cells of " + metres(cs),
                "fewer than 250 cells", "raise the cell size");
  }
  return cells;
}

/// The tile grid both builds use.
struct TileGrid {
  float originX = 0, originY = 0;  ///< lower corner of tile (0, 0) [m]
  float tileWidth = 0;             ///< [m]
  int tilesX = 0, tilesY = 0;
  int tileBits = 0;                ///< bits of a dtPolyRef spent on the tile index
};

/// Adds the built tiles (in index order, so polygon references do not depend on thread count)
/// to a new NavMeshData and fills its area table. Frees every tile's data on failure.
/// `nothingWalkable` is the diagnostic returned when no tile holds a polygon.
core::Result<NavMeshData*> assembleTiles(std::vector<TileOutput>& tiles, const TileGrid& grid,
                                         core::Diagnostic nothingWalkable);

}  // namespace throng::nav::detail

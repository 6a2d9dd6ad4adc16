// throng::nav::NavMesh::buildFromTerrain — the layered navmesh of a 3D world (floors above each
// other joined by stairs and ramps): validates the TerrainMesh, converts it to Recast's y-up order
// (scenario (x, y, z) is Recast (x, z, y)), sorts triangles into the same tile grid as the flat
// build, builds the tiles in parallel (terrain_tile.cpp) and assembles them in tile order, so
// polygon references are identical for any thread count. Reads the terrain and config once; the
// result is immutable.
#include <DetourNavMesh.h>
#include <Recast.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "build_common.hpp"
#include "navmesh_data.hpp"
#include "terrain_tile.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {
namespace {

using detail::diag;
using detail::ilog2Ceil;
using detail::kMinSaltBits;
using detail::kRefBits;
using detail::metres;

constexpr float kCellHeight = 0.1f;  // vertical voxel size [m]: maxClimb 0.35 m is 3 cells
constexpr float kHeightMargin = 1.0f;  // heightfield reaches this far below and above the geometry [m]

// Checks one triangle list: a multiple of 3 indices, each below vertexCount.
void validateTriangles(const std::vector<std::uint32_t>& tris, const char* name, std::size_t vertexCount,
                       core::Diagnostics& errors) {
  const std::string pointer = std::string("/terrain/") + name;
  if (tris.size() % 3 != 0) {
    errors.push_back(diag(pointer, "has " + std::to_string(tris.size()) + " indices",
                          "a multiple of 3 (three vertex indices per triangle)"));
  }
  for (std::size_t i = 0; i < tris.size(); ++i) {
    if (tris[i] < vertexCount) continue;
    errors.push_back(diag(pointer + "/" + std::to_string(i),
                          "vertex index " + std::to_string(tris[i]) + " is out of range",
                          "an index below the vertex count " + std::to_string(vertexCount)));
  }
}

/// The build settings and the terrain: every problem found, none when it can be built.
core::Diagnostics validateInput(const NavMeshConfig& cfg, const TerrainMesh& terrain) {
  core::Diagnostics errors;
  if (!std::isfinite(cfg.agentRadius) || cfg.agentRadius < 0.0f)
    errors.push_back(diag("/agentRadius", "agent radius is " + metres(cfg.agentRadius), "a radius >= 0 m"));
  if (!std::isfinite(cfg.maxSlopeDeg) || cfg.maxSlopeDeg <= 0.0f || cfg.maxSlopeDeg >= 90.0f)
    errors.push_back(diag("/maxSlopeDeg", "maximum slope is " + std::to_string(cfg.maxSlopeDeg) + " deg",
                          "a slope in (0, 90) degrees"));
  if (!std::isfinite(cfg.stairSlopeDeg) || cfg.stairSlopeDeg <= 0.0f || cfg.stairSlopeDeg >= 90.0f)
    errors.push_back(diag("/stairSlopeDeg", "stair slope is " + std::to_string(cfg.stairSlopeDeg) + " deg",
                          "a slope in (0, 90) degrees"));
  if (!std::isfinite(cfg.maxClimb) || cfg.maxClimb < 0.0f || cfg.maxClimb > 5.0f)
    errors.push_back(diag("/maxClimb", "maximum climb is " + metres(cfg.maxClimb), "a climb in [0, 5] m"));
  if (!std::isfinite(cfg.clearance) || cfg.clearance < kCellHeight || cfg.clearance > 25.0f)
    errors.push_back(diag("/clearance", "clearance is " + metres(cfg.clearance),
                          "a clearance in [" + metres(kCellHeight) + ", 25 m]"));

  const std::vector<float>& v = terrain.vertices;
  if (v.size() % 3 != 0) {
    errors.push_back(diag("/terrain/vertices", "has " + std::to_string(v.size()) + " coordinates",
                          "a multiple of 3 (x, y, z per vertex)"));
  }
  const std::size_t vertexCount = v.size() / 3;
  for (std::size_t i = 0; i < vertexCount * 3; ++i) {
    if (std::isfinite(v[i])) continue;
    errors.push_back(diag("/terrain/vertices/" + std::to_string(i), "coordinate is not finite",
                          "finite coordinates in metres"));
    break;  // one message is enough: the rest are likely the same problem
  }
  if (terrain.walkable.empty())
    errors.push_back(diag("/terrain/walkable", "no walkable triangles", "at least one walkable triangle"));
  validateTriangles(terrain.walkable, "walkable", vertexCount, errors);
  validateTriangles(terrain.obstacles, "obstacles", vertexCount, errors);
  return errors;
}

/// Ground bounds and height range of the walkable triangles.
struct WalkableExtent {
  core::Aabb box;
  float minZ = std::numeric_limits<float>::max();
  float maxZ = std::numeric_limits<float>::lowest();
};

WalkableExtent walkableExtent(const TerrainMesh& terrain) {
  WalkableExtent e;
  const std::size_t walkCount = terrain.walkable.size() / 3;
  for (std::size_t i = 0; i < walkCount * 3; ++i) {
    const float* p = &terrain.vertices[static_cast<std::size_t>(terrain.walkable[i]) * 3];
    e.box.min = {std::min(e.box.min.x, p[0]), std::min(e.box.min.y, p[1])};
    e.box.max = {std::max(e.box.max.x, p[0]), std::max(e.box.max.y, p[1])};
    e.minZ = std::min(e.minZ, p[2]);
    e.maxZ = std::max(e.maxZ, p[2]);
  }
  return e;
}

/// The voxel settings for this terrain: the automatic cell size (cfg.cellSize 0) chosen, the cell
/// and tile sizes and the height span checked, the erosion in cells.
core::Result<detail::TerrainSettings> terrainSettings(NavMeshConfig& cfg, const WalkableExtent& extent) {
  const core::Aabb& box = extent.box;
  if (cfg.cellSize == 0.0f) {  // automatic, as in NavMesh::build
    const double area = static_cast<double>(box.max.x - box.min.x) * static_cast<double>(box.max.y - box.min.y);
    const float bySize = static_cast<float>(std::sqrt(area / 4.0e7));
    cfg.cellSize = std::clamp(std::max(cfg.agentRadius * 0.25f, bySize), 0.03f, 0.3f);
  }
  core::Diagnostics errors;
  if (!std::isfinite(cfg.cellSize) || cfg.cellSize < 0.01f)
    errors.push_back(diag("/cellSize", "cell size is " + metres(cfg.cellSize), "a cell size >= 0.01 m (0 = automatic)"));
  else if (!std::isfinite(cfg.tileSize) || cfg.tileSize <= 4.0f * cfg.cellSize)
    errors.push_back(diag("/tileSize", "tile size is " + metres(cfg.tileSize),
                          "a tile size > 4 cell sizes (" + metres(4.0f * cfg.cellSize) + ")"));
  // Half a cell below the margin: a floor at the lowest height then lies mid-cell, not on a cell
  // boundary that float rounding could push either way (see the lift in terrain_tile.cpp).
  const float minY = extent.minZ - kHeightMargin - 0.5f * kCellHeight;
  const float maxY = extent.maxZ + cfg.clearance + kHeightMargin;
  if ((maxY - minY) / kCellHeight >= static_cast<float>(RC_SPAN_MAX_HEIGHT)) {
    errors.push_back(diag("/terrain/vertices",
                          "walkable heights span " + metres(extent.maxZ - extent.minZ) + " (from " + metres(extent.minZ) +
                              " to " + metres(extent.maxZ) + ")",
                          "at most " + metres(RC_SPAN_MAX_HEIGHT * kCellHeight - cfg.clearance - 2 * kHeightMargin) +
                              " between the lowest and highest walkable point"));
  }
  if (!errors.empty()) return errors;

  const float cs = cfg.cellSize;
  auto erosion = detail::erosionCells(cfg.agentRadius, cs);
  if (!erosion) return std::move(erosion).takeErrors();
  const int radiusCells = erosion.value();

  detail::TerrainSettings settings;
  settings.tile.cellSize = cs;
  settings.tile.tileCells = std::max(8, static_cast<int>(std::floor(cfg.tileSize / cs)));
  settings.tile.borderCells = radiusCells + 3;
  settings.tile.radiusCells = radiusCells;
  settings.tile.agentRadius = cfg.agentRadius;
  settings.tile.cuts = &cfg.cuts;
  settings.tile.layered = true;
  settings.tile.originX = box.min.x;
  settings.tile.originY = box.min.y;
  settings.cellHeight = kCellHeight;
  settings.minY = minY;
  settings.maxY = maxY;
  settings.maxSlopeDeg = cfg.maxSlopeDeg;
  settings.stairSlopeDeg = cfg.stairSlopeDeg;
  settings.walkableHeightCells = static_cast<int>(std::ceil(cfg.clearance / kCellHeight - 1e-4f));
  settings.walkableClimbCells = static_cast<int>(std::floor(cfg.maxClimb / kCellHeight + 1e-4f));
  return settings;
}

/// The tile grid over the walkable bounds; refused when Detour's polygon references cannot number
/// that many tiles.
core::Result<detail::TileGrid> tileGrid(const detail::TerrainSettings& settings, const core::Aabb& box) {
  detail::TileGrid grid;
  grid.originX = settings.tile.originX;
  grid.originY = settings.tile.originY;
  grid.tileWidth = static_cast<float>(settings.tile.tileCells) * settings.tile.cellSize;
  grid.tilesX = std::max(1, static_cast<int>(std::ceil((box.max.x - box.min.x) / grid.tileWidth)));
  grid.tilesY = std::max(1, static_cast<int>(std::ceil((box.max.y - box.min.y) / grid.tileWidth)));
  const long long tileCount = static_cast<long long>(grid.tilesX) * grid.tilesY;
  grid.tileBits = ilog2Ceil(static_cast<unsigned>(std::min<long long>(tileCount, 1u << 30)));
  if (grid.tileBits > kRefBits - kMinSaltBits - 4) {
    return diag("/tileSize", "the world needs " + std::to_string(grid.tilesX) + " x " + std::to_string(grid.tilesY) +
                                 " tiles of " + metres(grid.tileWidth) + ", too many for Detour's " +
                                 std::to_string(kRefBits) + "-bit polygon references",
                "at most " + std::to_string(1 << (kRefBits - kMinSaltBits - 4)) + " tiles", "raise tileSize");
  }
  return grid;
}

/// The terrain in Recast order, walkable triangles wound with their normal up (rcMarkWalkableTriangles
/// reads the winding; the input may have any).
detail::TerrainInput recastInput(const TerrainMesh& terrain) {
  const std::vector<float>& v = terrain.vertices;
  const std::size_t vertexCount = v.size() / 3;
  const std::size_t walkCount = terrain.walkable.size() / 3;
  const std::size_t obsCount = terrain.obstacles.size() / 3;
  detail::TerrainInput input;
  input.verts.resize(vertexCount * 3);
  for (std::size_t i = 0; i < vertexCount; ++i) {
    input.verts[i * 3 + 0] = v[i * 3 + 0];
    input.verts[i * 3 + 1] = v[i * 3 + 2];
    input.verts[i * 3 + 2] = v[i * 3 + 1];
  }
  input.walkable.assign(terrain.walkable.begin(), terrain.walkable.begin() + static_cast<std::ptrdiff_t>(walkCount * 3));
  input.obstacles.assign(terrain.obstacles.begin(),
                         terrain.obstacles.begin() + static_cast<std::ptrdiff_t>(obsCount * 3));
  for (std::size_t t = 0; t < walkCount; ++t) {
    int* tri = &input.walkable[t * 3];
    const float* a = &input.verts[static_cast<std::size_t>(tri[0]) * 3];
    const float* b = &input.verts[static_cast<std::size_t>(tri[1]) * 3];
    const float* c = &input.verts[static_cast<std::size_t>(tri[2]) * 3];
    // y of (b - a) x (c - a)
    const double ny = static_cast<double>(b[2] - a[2]) * (c[0] - a[0]) - static_cast<double>(b[0] - a[0]) * (c[2] - a[2]);
    if (ny < 0.0) std::swap(tri[1], tri[2]);
  }
  return input;
}

/// Triangles per tile (ascending triangle order), by ground bounding box against the tile plus
/// its border (one cell extra for rounding; Recast clips to the heightfield anyway).
std::vector<std::vector<int>> trianglesByTile(const detail::TerrainInput& input, const std::vector<int>& tris,
                                              const detail::TerrainSettings& settings, const detail::TileGrid& grid) {
  const int tilesX = grid.tilesX, tilesY = grid.tilesY;
  const float tileWidth = grid.tileWidth;
  std::vector<std::vector<int>> out(static_cast<std::size_t>(tilesX) * static_cast<std::size_t>(tilesY));
  const float reach = static_cast<float>(settings.tile.borderCells + 1) * settings.tile.cellSize;
  auto cell = [&](float value, float origin, int count) {
    const float f = std::floor((value - origin) / tileWidth);
    return static_cast<int>(std::clamp(f, 0.0f, static_cast<float>(count - 1)));
  };
  const float ox = settings.tile.originX, oy = settings.tile.originY;
  const std::size_t count = tris.size() / 3;
  for (std::size_t t = 0; t < count; ++t) {
    float x0 = std::numeric_limits<float>::max(), y0 = x0;
    float x1 = std::numeric_limits<float>::lowest(), y1 = x1;
    for (int k = 0; k < 3; ++k) {
      const float* p = &input.verts[static_cast<std::size_t>(tris[t * 3 + k]) * 3];
      x0 = std::min(x0, p[0]);
      x1 = std::max(x1, p[0]);
      y0 = std::min(y0, p[2]);
      y1 = std::max(y1, p[2]);
    }
    if (x1 + reach < ox || y1 + reach < oy) continue;
    if (x0 - reach > ox + tilesX * tileWidth || y0 - reach > oy + tilesY * tileWidth) continue;
    const int tx0 = cell(x0 - reach, ox, tilesX), tx1 = cell(x1 + reach, ox, tilesX);
    const int ty0 = cell(y0 - reach, oy, tilesY), ty1 = cell(y1 + reach, oy, tilesY);
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        out[static_cast<std::size_t>(ty) * static_cast<std::size_t>(tilesX) + static_cast<std::size_t>(tx)]
            .push_back(static_cast<int>(t));
  }
  return out;
}

/// Lowest and highest vertex of the ground polygons (Recast y); lo > hi when there are none.
std::pair<float, float> polygonHeightRange(const dtNavMesh& mesh) {
  float lo = std::numeric_limits<float>::max();
  float hi = std::numeric_limits<float>::lowest();
  for (int i = 0; i < mesh.getMaxTiles(); ++i) {
    const dtMeshTile* tile = mesh.getTile(i);
    if (!tile || !tile->header) continue;
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND) continue;
      for (int k = 0; k < poly.vertCount; ++k) {
        const float y = tile->verts[poly.verts[k] * 3 + 1];
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
    }
  }
  return {lo, hi};
}

}  // namespace

core::Result<std::shared_ptr<const NavMesh>> NavMesh::buildFromTerrain(const TerrainMesh& terrain,
                                                                       const NavMeshConfig& config) {
  NavMeshConfig cfg = config;
  if (auto errors = validateInput(cfg, terrain); !errors.empty()) return errors;
  const WalkableExtent extent = walkableExtent(terrain);
  auto settingsOr = terrainSettings(cfg, extent);
  if (!settingsOr) return std::move(settingsOr).takeErrors();
  const detail::TerrainSettings& settings = settingsOr.value();
  auto gridOr = tileGrid(settings, extent.box);
  if (!gridOr) return std::move(gridOr).takeErrors();
  const detail::TileGrid& grid = gridOr.value();

  const detail::TerrainInput input = recastInput(terrain);
  const std::vector<std::vector<int>> walkByTile = trianglesByTile(input, input.walkable, settings, grid);
  const std::vector<std::vector<int>> obsByTile = trianglesByTile(input, input.obstacles, settings, grid);
  const std::size_t tiles = walkByTile.size();
  std::vector<detail::TileOutput> built(tiles);
  tbb::parallel_for(std::size_t{0}, tiles, [&](std::size_t i) {
    if (detail::cancelled(cfg.cancel)) return;  // Ctrl-C: the remaining tiles are skipped
    const int tx = static_cast<int>(i % static_cast<std::size_t>(grid.tilesX));
    const int ty = static_cast<int>(i / static_cast<std::size_t>(grid.tilesX));
    built[i] = detail::buildTerrainTile(settings, tx, ty, input, walkByTile[i], obsByTile[i]);
  });
  if (detail::cancelled(cfg.cancel)) {
    return diag("", "interrupted: the navigation mesh build was stopped by a signal", "");
  }

  auto assembled = detail::assembleTiles(
      built, grid,
      diag("/terrain/walkable",
           "nothing walkable remains (slopes up to " + std::to_string(cfg.maxSlopeDeg) + " deg, " +
               metres(cfg.clearance) + " of headroom, eroded by the agent radius " + metres(cfg.agentRadius) + ")",
           "walkable surfaces wider than " + metres(2.0f * cfg.agentRadius) + " with " + metres(cfg.clearance) +
               " of headroom"));
  if (!assembled.ok()) return std::move(assembled).takeErrors();
  detail::NavMeshData* mesh = assembled.value();
  const auto [lo, hi] = polygonHeightRange(*mesh);

  std::shared_ptr<NavMesh> out(new NavMesh());
  out->mesh_ = mesh;
  out->config_ = cfg;
  out->config_.cancel = nullptr;  // only for the build: the flag need not outlive it
  out->bounds_ = extent.box;
  out->layered_ = true;
  out->minHeight_ = lo <= hi ? lo : 0.0f;
  out->maxHeight_ = lo <= hi ? hi : 0.0f;
  return std::shared_ptr<const NavMesh>(std::move(out));
}

}  // namespace throng::nav

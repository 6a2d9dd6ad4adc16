// throng::nav::NavMesh — builds the tiled Recast/Detour navmesh of the walkable area (walkable
// polygons minus obstacles, eroded by the agent radius) on the plane y = 0, and assembles built
// tiles (of this build or of NavMesh::buildFromTerrain, terrain_builder.cpp) into the dtNavMesh.
// Reads the polygons and config once; the result is immutable. Tiles build in parallel (oneTBB) and are added to the
// dtNavMesh in tile order, so polygon references are identical for any thread count. Also answers
// what the ground of one polygon is like (NavMesh::surface: stair or floor, mean gradient).
#include "throng/nav/navmesh.hpp"

#include <DetourAlloc.h>
#include <DetourCommon.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "build_common.hpp"
#include "throng/core/assert.hpp"
#include "navmesh_data.hpp"
#include "tile_builder.hpp"

namespace throng::nav {
namespace {

using detail::diag;
using detail::ilog2Ceil;
using detail::kMinSaltBits;
using detail::kRefBits;
using detail::metres;

void validatePolygons(std::span<const Polygon> polys, const char* name, core::Diagnostics& errors) {
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const std::string pointer = std::string("/") + name + "/" + std::to_string(i);
    if (polys[i].size() < 3) {
      errors.push_back(diag(pointer, "polygon has " + std::to_string(polys[i].size()) + " vertices",
                            "at least 3 vertices"));
      continue;
    }
    for (const Vec2& p : polys[i]) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        errors.push_back(diag(pointer, "polygon has a non-finite coordinate", "finite coordinates in metres"));
        break;
      }
    }
  }
}

}  // namespace

namespace detail {
namespace {

// Area of polygon `poly` of `tile` in the xz-plane [m²].
double polyArea(const dtMeshTile& tile, const dtPoly& poly) {
  double area = 0.0;
  for (int k = 0, j = poly.vertCount - 1; k < poly.vertCount; j = k++) {
    const float* a = &tile.verts[poly.verts[j] * 3];
    const float* b = &tile.verts[poly.verts[k] * 3];
    area += static_cast<double>(a[0]) * b[2] - static_cast<double>(b[0]) * a[2];
  }
  return std::abs(area) * 0.5;
}

}  // namespace

core::Result<NavMeshData*> assembleTiles(std::vector<TileOutput>& tiles, const TileGrid& grid,
                                         core::Diagnostic nothingWalkable) {
  auto freeAll = [&tiles] {
    for (auto& t : tiles) {
      if (t.data) dtFree(t.data);
      t.data = nullptr;
    }
  };
  const auto tilesX = static_cast<std::size_t>(grid.tilesX);
  const std::size_t tileCount = tiles.size();
  core::Diagnostics errors;
  int maxPolys = 0;
  std::size_t usedTiles = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    if (!tiles[i].error.empty()) {
      errors.push_back(diag("", "tile (" + std::to_string(i % tilesX) + ", " + std::to_string(i / tilesX) +
                                    "): " + tiles[i].error,
                            "a successful Recast build"));
    }
    maxPolys = std::max(maxPolys, tiles[i].polyCount);
    if (tiles[i].data) ++usedTiles;
  }
  if (!errors.empty()) {
    freeAll();
    return errors;
  }
  if (usedTiles == 0) return nothingWalkable;
  const int tileBits = grid.tileBits;
  const int polyBits = std::max(1, ilog2Ceil(static_cast<unsigned>(maxPolys)));
  if (tileBits + polyBits > kRefBits - kMinSaltBits) {
    freeAll();
    return diag("/tileSize",
                "a tile holds up to " + std::to_string(maxPolys) + " polygons and there are " +
                    std::to_string(tileCount) + " tiles: too many for Detour's " + std::to_string(kRefBits) +
                    "-bit polygon references",
                "tile bits + polygon bits <= " + std::to_string(kRefBits - kMinSaltBits),
                "change tileSize (smaller tiles hold fewer polygons, larger tiles mean fewer tiles)");
  }

  auto* mesh = new NavMeshData();
  dtNavMeshParams params{};
  params.orig[0] = grid.originX;
  params.orig[1] = 0.0f;
  params.orig[2] = grid.originY;
  params.tileWidth = grid.tileWidth;
  params.tileHeight = grid.tileWidth;
  params.maxTiles = 1 << tileBits;
  params.maxPolys = 1 << polyBits;
  if (dtStatusFailed(mesh->init(&params))) {
    delete mesh;
    freeAll();
    return diag("", "Detour could not initialise a navmesh of " + std::to_string(tileCount) + " tiles",
                "a successful dtNavMesh::init");
  }
  for (auto& t : tiles) {
    if (!t.data) continue;
    if (dtStatusFailed(mesh->addTile(t.data, t.size, DT_TILE_FREE_DATA, 0, nullptr))) {
      delete mesh;
      freeAll();
      return diag("", "Detour rejected a tile", "a successful dtNavMesh::addTile");
    }
    t.data = nullptr;  // owned by the mesh now
  }

  // Area table for randomPoint, in tile-index then polygon-index order.
  const dtNavMesh& constMesh = *mesh;
  double total = 0.0;
  for (int i = 0; i < constMesh.getMaxTiles(); ++i) {
    const dtMeshTile* tile = constMesh.getTile(i);
    if (!tile || !tile->header) continue;
    const dtPolyRef base = constMesh.getPolyRefBase(tile);
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND) continue;
      total += polyArea(*tile, poly);
      mesh->areas.push_back({base | static_cast<dtPolyRef>(p), total});
    }
  }
  return mesh;
}

}  // namespace detail

float NavMesh::narrowestOpening() const {
  const auto cells = detail::erosionCells(config_.agentRadius, config_.cellSize);
  return cells ? 2.0f * static_cast<float>(cells.value()) * config_.cellSize : 2.0f * config_.agentRadius;
}

core::Result<std::shared_ptr<const NavMesh>> NavMesh::build(std::span<const Polygon> walkable,
                                                          std::span<const Polygon> obstacles,
                                                          const NavMeshConfig& config) {
  core::Diagnostics errors;
  NavMeshConfig cfg = config;
  if (!std::isfinite(cfg.agentRadius) || cfg.agentRadius < 0.0f)
    errors.push_back(diag("/agentRadius", "agent radius is " + metres(cfg.agentRadius), "a radius >= 0 m"));
  if (cfg.cellSize == 0.0f) {
    // Automatic: a quarter of the radius (erosion error is about one cell, so a 1 m door keeps
    // 0.5 m for agent centres at r = 0.2 m), coarser for huge worlds so the raster stays near
    // 40 million cells (a 1 km square builds in seconds).
    double area = 0.0;
    core::Aabb box;
    for (const Polygon& p : walkable) for (const Vec2& v : p) box.extend(v);
    if (box.valid()) area = static_cast<double>(box.max.x - box.min.x) * static_cast<double>(box.max.y - box.min.y);
    const float bySize = static_cast<float>(std::sqrt(area / 4.0e7));
    cfg.cellSize = std::clamp(std::max(cfg.agentRadius * 0.25f, bySize), 0.03f, 0.3f);
  }
  if (!std::isfinite(cfg.cellSize) || cfg.cellSize < 0.01f)
    errors.push_back(diag("/cellSize", "cell size is " + metres(cfg.cellSize), "a cell size >= 0.01 m (0 = automatic)"));
  else if (!std::isfinite(cfg.tileSize) || cfg.tileSize <= 4.0f * cfg.cellSize)
    errors.push_back(diag("/tileSize", "tile size is " + metres(cfg.tileSize),
                          "a tile size > 4 cell sizes (" + metres(4.0f * cfg.cellSize) + ")"));
  if (walkable.empty()) errors.push_back(diag("/walkable", "no walkable polygons", "at least one walkable polygon"));
  validatePolygons(walkable, "walkable", errors);
  validatePolygons(obstacles, "obstacles", errors);
  if (!errors.empty()) return errors;

  const float cs = cfg.cellSize;
  auto erosion = detail::erosionCells(cfg.agentRadius, cs);
  if (!erosion) return std::move(erosion).takeErrors();
  const int radiusCells = erosion.value();

  core::Aabb box;
  for (const Polygon& poly : walkable) {
    for (const Vec2& p : poly) {
      box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y)};
      box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y)};
    }
  }
  detail::TileSettings settings;
  settings.cellSize = cs;
  settings.tileCells = std::max(8, static_cast<int>(std::floor(cfg.tileSize / cs)));
  settings.borderCells = radiusCells + 3;
  settings.radiusCells = radiusCells;
  settings.agentRadius = cfg.agentRadius;
  settings.cuts = &cfg.cuts;
  settings.originX = box.min.x;
  settings.originY = box.min.y;
  const float tileWidth = static_cast<float>(settings.tileCells) * cs;
  const int tilesX = std::max(1, static_cast<int>(std::ceil((box.max.x - box.min.x) / tileWidth)));
  const int tilesY = std::max(1, static_cast<int>(std::ceil((box.max.y - box.min.y) / tileWidth)));
  const long long tileCount = static_cast<long long>(tilesX) * tilesY;
  const int tileBits = ilog2Ceil(static_cast<unsigned>(std::min<long long>(tileCount, 1u << 30)));
  if (tileBits > kRefBits - kMinSaltBits - 4) {
    return diag("/tileSize", "the world needs " + std::to_string(tilesX) + " x " + std::to_string(tilesY) +
                                 " tiles of " + metres(tileWidth) + ", too many for Detour's " +
                                 std::to_string(kRefBits) + "-bit polygon references",
                "at most " + std::to_string(1 << (kRefBits - kMinSaltBits - 4)) + " tiles", "raise tileSize");
  }

  const auto walkRaster = detail::prepare(walkable);
  const auto obstacleRaster = detail::prepare(obstacles);
  std::vector<detail::TileOutput> tiles(static_cast<std::size_t>(tileCount));
  tbb::parallel_for(std::size_t{0}, tiles.size(), [&](std::size_t i) {
    if (detail::cancelled(cfg.cancel)) return;  // Ctrl-C: the remaining tiles are skipped
    const int tx = static_cast<int>(i % static_cast<std::size_t>(tilesX));
    const int ty = static_cast<int>(i / static_cast<std::size_t>(tilesX));
    tiles[i] = detail::buildTile(settings, tx, ty, walkRaster, obstacleRaster);
  });
  if (detail::cancelled(cfg.cancel)) {
    return diag("", "interrupted: the navigation mesh build was stopped by a signal", "");
  }
  detail::TileGrid grid;
  grid.originX = settings.originX;
  grid.originY = settings.originY;
  grid.tileWidth = tileWidth;
  grid.tilesX = tilesX;
  grid.tilesY = tilesY;
  grid.tileBits = tileBits;
  auto assembled = detail::assembleTiles(
      tiles, grid,
      diag("/walkable", "nothing walkable remains after eroding by the agent radius " + metres(cfg.agentRadius),
           "walkable areas wider than " + metres(2.0f * cfg.agentRadius)));
  if (!assembled.ok()) return std::move(assembled).takeErrors();
  detail::NavMeshData* mesh = assembled.value();

  std::shared_ptr<NavMesh> out(new NavMesh());
  out->mesh_ = mesh;
  out->config_ = cfg;
  out->config_.cancel = nullptr;  // only for the build: the flag need not outlive it
  out->bounds_ = box;
  return std::shared_ptr<const NavMesh>(std::move(out));
}

NavMesh::~NavMesh() { delete static_cast<detail::NavMeshData*>(mesh_); }

std::size_t NavMesh::polygonCount() const { return detail::data(*this).areas.size(); }

std::vector<Polygon> NavMesh::polygons() const {
  std::vector<Polygon> out;
  const dtNavMesh& mesh = *mesh_;
  for (int i = 0; i < mesh.getMaxTiles(); ++i) {
    const dtMeshTile* tile = mesh.getTile(i);
    if (!tile || !tile->header) continue;
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND) continue;
      Polygon outline;
      outline.reserve(poly.vertCount);
      for (int k = 0; k < poly.vertCount; ++k) outline.push_back(detail::fromRecast(&tile->verts[poly.verts[k] * 3]));
      out.push_back(std::move(outline));
    }
  }
  return out;
}

std::vector<core::Segment> NavMesh::boundary(std::vector<float>* heights) const {
  std::vector<core::Segment> out;
  const dtNavMesh* nav = mesh_;
  if (nav == nullptr) return out;
  for (int t = 0; t < nav->getMaxTiles(); ++t) {
    const dtMeshTile* tile = nav->getTile(t);
    if (tile == nullptr || tile->header == nullptr) continue;
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND) continue;
      for (int e = 0; e < poly.vertCount; ++e) {
        bool boundary;
        if (poly.neis[e] & DT_EXT_LINK) {
          // Tile border: a wall only where no link crosses this edge.
          boundary = true;
          for (unsigned int k = poly.firstLink; k != DT_NULL_LINK; k = tile->links[k].next) {
            if (tile->links[k].edge == e) { boundary = false; break; }
          }
        } else {
          boundary = poly.neis[e] == 0;
        }
        if (!boundary) continue;
        const float* va = &tile->verts[poly.verts[e] * 3];
        const float* vb = &tile->verts[poly.verts[(e + 1) % poly.vertCount] * 3];
        // Recast is y-up: our plane is (x, z).
        out.push_back({core::Vec2{va[0], va[2]}, core::Vec2{vb[0], vb[2]}});
        if (heights) {
          heights->push_back(va[1]);
          heights->push_back(vb[1]);
        }
      }
    }
  }
  return out;
}

Surface NavMesh::surface(PolyRef ref) const {
  const dtMeshTile* tile = nullptr;
  const dtPoly* poly = nullptr;
  if (ref == 0 || dtStatusFailed(mesh_->getTileAndPolyByRef(static_cast<dtPolyRef>(ref), &tile, &poly))) return {};
  Surface out;
  out.stair = poly->getArea() == kStairArea;
  if (!layered_) return out;
  // The sum of the detail triangles' normals, each as long as twice its triangle's area and turned
  // up, is the surface's vector area: its horizontal part over its vertical part is minus the mean
  // gradient over the polygon's ground area (Recast order: y up).
  const auto ip = static_cast<std::size_t>(poly - tile->polys);
  const dtPolyDetail& pd = tile->detailMeshes[ip];
  const auto vertex = [&](unsigned char k) {
    return k < poly->vertCount ? &tile->verts[poly->verts[k] * 3] : &tile->detailVerts[(pd.vertBase + k - poly->vertCount) * 3];
  };
  double nx = 0.0, ny = 0.0, nz = 0.0;
  for (unsigned t = 0; t < pd.triCount; ++t) {
    const unsigned char* tri = &tile->detailTris[(pd.triBase + t) * 4];
    const float* a = vertex(tri[0]);
    const float* b = vertex(tri[1]);
    const float* c = vertex(tri[2]);
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[1] < 0.0) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    nx += n[0];
    ny += n[1];
    nz += n[2];
  }
  if (ny > 1e-12) out.gradient = Vec2{static_cast<float>(-nx / ny), static_cast<float>(-nz / ny)};
  return out;
}

bool CutRegion::contains(Vec2 p, float margin) const {
  if (polygon.empty()) return core::lengthSq(p - centre) <= (radius + margin) * (radius + margin);
  return core::pointInPolygon(polygon, p) || (margin > 0.0f && core::distanceToBoundary(polygon, p) <= margin);
}

std::shared_ptr<NavMesh> NavMesh::clone() const {
  const dtNavMesh& from = *mesh_;
  auto* copy = new detail::NavMeshData();
  copy->areas = detail::data(*this).areas;
  std::shared_ptr<NavMesh> out(new NavMesh());
  out->mesh_ = copy;
  out->config_ = config_;
  out->bounds_ = bounds_;
  out->layered_ = layered_;
  out->minHeight_ = minHeight_;
  out->maxHeight_ = maxHeight_;
  [[maybe_unused]] const dtStatus init = copy->init(from.getParams());
  THRONG_ASSERT(!dtStatusFailed(init));
  // The tiles in slot order, each at the reference it had (so every PolyRef stays valid).
  for (int i = 0; i < from.getMaxTiles(); ++i) {
    const dtMeshTile* tile = from.getTile(i);
    if (tile == nullptr || tile->header == nullptr || tile->dataSize <= 0) continue;
    auto* bytes = static_cast<unsigned char*>(dtAlloc(static_cast<std::size_t>(tile->dataSize), DT_ALLOC_PERM));
    THRONG_ASSERT(bytes != nullptr);
    std::memcpy(bytes, tile->data, static_cast<std::size_t>(tile->dataSize));
    const dtTileRef ref = from.getTileRef(tile);
    [[maybe_unused]] const dtStatus added = copy->addTile(bytes, tile->dataSize, DT_TILE_FREE_DATA, ref, nullptr);
    THRONG_ASSERT(!dtStatusFailed(added));  // the same slots, free in a new mesh (links are rebuilt)
  }
  return out;
}

std::vector<PolyRef> NavMesh::cutPolygons(const CutRegion& region) const {
  std::vector<PolyRef> out;
  const dtNavMesh& mesh = *mesh_;
  for (int i = 0; i < mesh.getMaxTiles(); ++i) {
    const dtMeshTile* tile = mesh.getTile(i);
    if (tile == nullptr || tile->header == nullptr) continue;
    const dtPolyRef base = mesh.getPolyRefBase(tile);
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND || (poly.flags & kCutFlag) == 0) continue;
      double x = 0.0, y = 0.0, z = 0.0;
      for (int k = 0; k < poly.vertCount; ++k) {
        const float* v = &tile->verts[poly.verts[k] * 3];
        x += v[0], y += v[1], z += v[2];
      }
      const double n = poly.vertCount;
      const Vec2 centroid{static_cast<float>(x / n), static_cast<float>(z / n)};
      if (!region.contains(centroid, kCutMargin * config_.cellSize)) continue;
      if (layered_ && std::abs(static_cast<float>(y / n) - region.height) > kLevelSearch) continue;
      out.push_back(base | static_cast<dtPolyRef>(p));
    }
  }
  return out;
}

bool NavMesh::floorIn(const CutRegion& region) const {
  const dtNavMesh& mesh = *mesh_;
  std::vector<Vec2> outline;
  for (int i = 0; i < mesh.getMaxTiles(); ++i) {
    const dtMeshTile* tile = mesh.getTile(i);
    if (tile == nullptr || tile->header == nullptr) continue;
    for (int p = 0; p < tile->header->polyCount; ++p) {
      const dtPoly& poly = tile->polys[p];
      if (poly.getType() != DT_POLYTYPE_GROUND) continue;
      outline.clear();
      double height = 0.0;
      for (int k = 0; k < poly.vertCount; ++k) {
        const float* v = &tile->verts[poly.verts[k] * 3];
        outline.push_back({v[0], v[2]});
        height += v[1];
      }
      if (layered_ && std::abs(static_cast<float>(height / poly.vertCount) - region.height) > kLevelSearch) continue;
      // A disc overlaps a polygon holding its centre or an edge within its radius; two simple
      // outlines overlap when a vertex of one lies in the other or two edges cross.
      const core::Polygon& r = region.polygon;
      const bool disc = r.empty();
      if (disc ? core::pointInPolygon(outline, region.centre) : core::pointInPolygon(outline, r[0])) return true;
      for (std::size_t k = 0, j = outline.size() - 1; k < outline.size(); j = k++) {
        if (disc ? core::distanceToSegmentSq(region.centre, outline[j], outline[k]) <= region.radius * region.radius
                 : region.contains(outline[k])) {
          return true;
        }
        for (std::size_t m = 0, n = r.size() - 1; m < r.size(); n = m++) {
          if (core::segmentsIntersect(outline[j], outline[k], r[n], r[m])) return true;
        }
      }
    }
  }
  return false;
}

void NavMesh::setClosed(std::span<const PolyRef> polys, bool closed) {
  for (const PolyRef ref : polys) {
    (void)mesh_->setPolyFlags(static_cast<dtPolyRef>(ref), closed ? kCutFlag : (kWalkFlag | kCutFlag));
  }
}

}  // namespace throng::nav

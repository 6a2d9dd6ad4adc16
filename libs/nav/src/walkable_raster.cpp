// throng::nav (private) — scanline rasterization of the walkable area; see walkable_raster.hpp.
#include "walkable_raster.hpp"

#include <algorithm>
#include <cmath>

namespace throng::nav::detail {

std::vector<RasterPolygon> prepare(std::span<const core::Polygon> polygons) {
  std::vector<RasterPolygon> out;
  out.reserve(polygons.size());
  for (const core::Polygon& poly : polygons) {
    RasterPolygon r;
    r.points = &poly;
    r.minX = r.minY = 1e30f;
    r.maxX = r.maxY = -1e30f;
    for (const core::Vec2& p : poly) {
      r.minX = std::min(r.minX, p.x);
      r.minY = std::min(r.minY, p.y);
      r.maxX = std::max(r.maxX, p.x);
      r.maxY = std::max(r.maxY, p.y);
    }
    out.push_back(r);
  }
  return out;
}

std::vector<const RasterPolygon*> overlapping(const std::vector<RasterPolygon>& all, float minX, float minY,
                                              float maxX, float maxY) {
  std::vector<const RasterPolygon*> out;
  for (const RasterPolygon& r : all) {
    if (r.maxX >= minX && r.minX <= maxX && r.maxY >= minY && r.minY <= maxY) out.push_back(&r);
  }
  return out;
}

namespace {

/// The edges of some polygons that cross each row's centre line, bucketed by row (in polygon
/// order within a row): a row visits only its own crossings, so a polygon of n vertices costs
/// O(n + crossings) per tile instead of O(n) per row (200,000 vertices × 1,000 rows was minutes).
struct RowEdges {
  struct Edge {
    std::uint32_t polygon;  ///< index into the polygon list
    core::Vec2 a, b;        ///< a = previous vertex, b = this one (markRow's order)
  };
  std::vector<std::uint32_t> start;  ///< row r's edges: edges[start[r] .. start[r + 1])
  std::vector<Edge> edges;
};

float rowCentre(float originY, float cellSize, int row) { return originY + (static_cast<float>(row) + 0.5f) * cellSize; }

/// Rows whose centre yc has (a.y <= yc) != (b.y <= yc) — the half-open rule of the scanline.
template <typename Visit>
void forEachRow(core::Vec2 a, core::Vec2 b, float originY, float cellSize, int height, Visit&& visit) {
  if (a.y == b.y) return;
  const double lo = (static_cast<double>(std::min(a.y, b.y)) - originY) / cellSize - 0.5;
  const double hi = (static_cast<double>(std::max(a.y, b.y)) - originY) / cellSize - 0.5;
  if (!(hi >= -1.0) || !(lo <= static_cast<double>(height))) return;
  const int r0 = static_cast<int>(std::max(0.0, std::floor(lo) - 1.0));
  const int r1 = static_cast<int>(std::min(static_cast<double>(height - 1), std::ceil(hi) + 1.0));
  for (int r = r0; r <= r1; ++r) {
    const float yc = rowCentre(originY, cellSize, r);
    if ((a.y <= yc) != (b.y <= yc)) visit(r);  // exactly the test markRow made
  }
}

RowEdges bucketEdges(std::span<const RasterPolygon* const> polygons, float originY, float cellSize, int height) {
  RowEdges out;
  out.start.assign(static_cast<std::size_t>(height) + 1, 0);
  for (const RasterPolygon* poly : polygons) {
    const core::Polygon& pts = *poly->points;
    for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
      forEachRow(pts[j], pts[i], originY, cellSize, height, [&](int r) { ++out.start[static_cast<std::size_t>(r) + 1]; });
    }
  }
  for (std::size_t r = 1; r < out.start.size(); ++r) out.start[r] += out.start[r - 1];
  out.edges.resize(out.start.back());
  std::vector<std::uint32_t> fill(out.start.begin(), out.start.end() - 1);
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const core::Polygon& pts = *polygons[k]->points;
    for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
      forEachRow(pts[j], pts[i], originY, cellSize, height, [&](int r) {
        out.edges[fill[static_cast<std::size_t>(r)]++] = RowEdges::Edge{static_cast<std::uint32_t>(k), pts[j], pts[i]};
      });
    }
  }
  return out;
}

// Adds +1/-1 coverage marks for the cells of row `row` whose centres lie inside each polygon
// (even-odd per polygon), from the row's bucketed edges.
void markRow(const RowEdges& rows, int row, float yc, float originX, float cellSize, int width, std::vector<float>& crossings,
             std::vector<int>& diff) {
  const std::uint32_t begin = rows.start[static_cast<std::size_t>(row)];
  const std::uint32_t end = rows.start[static_cast<std::size_t>(row) + 1];
  for (std::uint32_t e = begin; e < end;) {
    const std::uint32_t polygon = rows.edges[e].polygon;
    crossings.clear();
    for (; e < end && rows.edges[e].polygon == polygon; ++e) {
      const core::Vec2 a = rows.edges[e].a;
      const core::Vec2 b = rows.edges[e].b;
      const double t = (static_cast<double>(yc) - a.y) / (static_cast<double>(b.y) - a.y);
      crossings.push_back(static_cast<float>(a.x + t * (static_cast<double>(b.x) - a.x)));
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
      // Cell c is covered when x0 <= originX + (c + 0.5) * cellSize < x1.
      const double c0 = std::ceil((crossings[k] - originX) / cellSize - 0.5);
      const double c1 = std::ceil((crossings[k + 1] - originX) / cellSize - 0.5);
      const int i0 = static_cast<int>(std::clamp(c0, 0.0, static_cast<double>(width)));
      const int i1 = static_cast<int>(std::clamp(c1, 0.0, static_cast<double>(width)));
      if (i0 >= i1) continue;
      diff[i0] += 1;
      diff[i1] -= 1;
    }
  }
}

}  // namespace

std::vector<std::uint8_t> rasterizeWalkable(std::span<const RasterPolygon* const> walkable,
                                            std::span<const RasterPolygon* const> obstacles, float originX,
                                            float originY, float cellSize, int width, int height) {
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  if (width <= 0 || height <= 0) return cells;
  std::vector<int> walkDiff(static_cast<std::size_t>(width) + 1);
  std::vector<int> obstacleDiff(static_cast<std::size_t>(width) + 1);
  std::vector<float> crossings;
  const RowEdges walkRows = bucketEdges(walkable, originY, cellSize, height);
  const RowEdges obstacleRows = bucketEdges(obstacles, originY, cellSize, height);
  for (int row = 0; row < height; ++row) {
    const float yc = rowCentre(originY, cellSize, row);
    if (walkRows.start[static_cast<std::size_t>(row)] == walkRows.start[static_cast<std::size_t>(row) + 1]) continue;
    std::fill(walkDiff.begin(), walkDiff.end(), 0);
    std::fill(obstacleDiff.begin(), obstacleDiff.end(), 0);
    markRow(walkRows, row, yc, originX, cellSize, width, crossings, walkDiff);
    markRow(obstacleRows, row, yc, originX, cellSize, width, crossings, obstacleDiff);
    int walk = 0;
    int blocked = 0;
    std::uint8_t* out = cells.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(width);
    for (int c = 0; c < width; ++c) {
      walk += walkDiff[c];
      blocked += obstacleDiff[c];
      out[c] = (walk > 0 && blocked == 0) ? 1 : 0;
    }
  }
  return cells;
}

}  // namespace throng::nav::detail

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

// Adds +1/-1 coverage marks for the cells of one row whose centres lie inside `poly` (even-odd).
void markRow(const RasterPolygon& poly, float yc, float originX, float cellSize, int width,
             std::vector<float>& crossings, std::vector<int>& diff) {
  if (yc < poly.minY || yc >= poly.maxY) return;
  const core::Polygon& pts = *poly.points;
  crossings.clear();
  const std::size_t n = pts.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const core::Vec2 a = pts[j];
    const core::Vec2 b = pts[i];
    // Half-open rule: a vertex exactly on the scanline counts for one of its two edges only.
    if ((a.y <= yc) == (b.y <= yc)) continue;
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

}  // namespace

std::vector<std::uint8_t> rasterizeWalkable(std::span<const RasterPolygon* const> walkable,
                                            std::span<const RasterPolygon* const> obstacles, float originX,
                                            float originY, float cellSize, int width, int height) {
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  std::vector<int> walkDiff(static_cast<std::size_t>(width) + 1);
  std::vector<int> obstacleDiff(static_cast<std::size_t>(width) + 1);
  std::vector<float> crossings;
  for (int row = 0; row < height; ++row) {
    const float yc = originY + (static_cast<float>(row) + 0.5f) * cellSize;
    std::fill(walkDiff.begin(), walkDiff.end(), 0);
    std::fill(obstacleDiff.begin(), obstacleDiff.end(), 0);
    bool any = false;
    for (const RasterPolygon* poly : walkable) {
      if (yc < poly->minY || yc >= poly->maxY) continue;
      markRow(*poly, yc, originX, cellSize, width, crossings, walkDiff);
      any = true;
    }
    if (!any) continue;
    for (const RasterPolygon* poly : obstacles) markRow(*poly, yc, originX, cellSize, width, crossings, obstacleDiff);
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

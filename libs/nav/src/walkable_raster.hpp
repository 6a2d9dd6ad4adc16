// throng::nav (private) — rasterizes "inside some walkable polygon and outside every obstacle" onto
// a grid of cells by scanlines, testing each cell's centre with the even-odd rule per polygon. Exact
// for concave polygons, overlapping walkable polygons and obstacles that cross the walkable
// boundary. Reads polygons only; writes one byte per cell (1 = walkable).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::nav::detail {

/// A polygon with its bounding box, prepared once per build.
struct RasterPolygon {
  const core::Polygon* points = nullptr;
  float minX = 0, minY = 0, maxX = 0, maxY = 0;
};

std::vector<RasterPolygon> prepare(std::span<const core::Polygon> polygons);

/// Polygons whose bounding box overlaps [minX,maxX]x[minY,maxY].
std::vector<const RasterPolygon*> overlapping(const std::vector<RasterPolygon>& all, float minX, float minY,
                                              float maxX, float maxY);

/// Grid of width x height cells of edge `cellSize` whose lower corner is (originX, originY).
/// Result index = row * width + column; row runs along +y.
std::vector<std::uint8_t> rasterizeWalkable(std::span<const RasterPolygon* const> walkable,
                                            std::span<const RasterPolygon* const> obstacles, float originX,
                                            float originY, float cellSize, int width, int height);

}  // namespace throng::nav::detail

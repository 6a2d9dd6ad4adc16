// throng::core footprints — ground-plane triangles (a glTF mesh projected: x → x, −z → y) →
// the polygons they cover: the union of the triangles (Boost.Geometry, cascaded pairwise so
// thousands of triangles stay fast), coordinates snapped to 1 mm, collinear vertices removed,
// degenerate (vertical) triangles dropped. Reads and writes memory only. Used by the glTF world
// loader (throng::io) for floors and obstacles and by the recorder for a multi-level world's 2D geometry.
#pragma once
#include <array>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::core {

struct Footprint {
  std::vector<Polygon> outer;  ///< outer rings, counter-clockwise
  std::vector<Polygon> holes;  ///< holes of those rings (for a floor: places not to walk), any winding
};

/// The union of the triangles. Triangles with an area below 1 mm² are ignored.
[[nodiscard]] Footprint unionOfTriangles(const std::vector<std::array<Vec2, 3>>& triangles);

}  // namespace throng::core

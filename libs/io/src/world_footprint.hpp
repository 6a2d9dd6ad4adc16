// throng::io world footprints — ground-plane triangles (a glTF mesh projected: x → x, −z → y) →
// the polygons they cover: the union of the triangles (Boost.Geometry, cascaded pairwise so
// thousands of triangles stay fast), coordinates snapped to 1 mm, collinear vertices removed,
// degenerate (vertical) triangles dropped. Reads and writes memory only. Private to throng_io.
#pragma once
#include <array>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::io {

struct Footprint {
  std::vector<core::Polygon> outer;  ///< outer rings, counter-clockwise
  std::vector<core::Polygon> holes;  ///< holes of those rings (for a floor: places not to walk), any winding
};

/// The union of the triangles. Triangles with an area below 1 mm² are ignored.
[[nodiscard]] Footprint unionOfTriangles(const std::vector<std::array<core::Vec2, 3>>& triangles);

}  // namespace throng::io

// throng::recording walkable-area WKT — the walkable area of a scenario (union of the walkable polygons
// minus the obstacles) as the WKT a JuPedSim recording stores in `geometry.wkt`. Reads the
// scenario's polygons; writes a string. Computed with Boost.Geometry so that obstacles touching
// or crossing the walkable boundary still give a valid (OGC / shapely) polygon.
#pragma once
#include <string>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::recording {

struct WalkableAreaWkt {
  std::string wkt;      ///< "POLYGON ((…), (…))", "MULTIPOLYGON (…)" when disconnected, or "POLYGON EMPTY"
  double area = 0.0;    ///< [m²]
  double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;  ///< bounds [m]; all 0 when empty
  std::size_t parts = 0;  ///< polygons in the result (1 for a connected area)
  bool valid = false;   ///< boost::geometry::is_valid on the result (OGC validity)
};

/// Union of `walkable` minus every obstacle. Exteriors are counter-clockwise, holes clockwise,
/// rings closed; coordinates are the shortest decimals of the scenario's floats.
[[nodiscard]] WalkableAreaWkt walkableAreaWkt(const std::vector<core::Polygon>& walkable,
                                              const std::vector<core::Polygon>& obstacles);

/// WKT of a single polygon (a point's region, a spawn polygon), closed and counter-clockwise.
[[nodiscard]] std::string polygonWkt(const core::Polygon& polygon);

}  // namespace throng::recording

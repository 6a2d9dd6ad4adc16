// throng::io scenario parser — JSON document → sim::ScenarioDesc, checking keys, types, ranges
// and each polygon on its own (simple, non-degenerate), a multi-level world's "terrain" (vertices
// and triangle indices), heights of positions, id references (goals, spawn points, the
// crowd model's "follow" population and group) and the crowd-model keys (Musse et al.).
// Geometric cross-element checks (spawn and guide waypoints inside the walkable area, capacity,
// reachability) belong to scenario_validator. Reads a JsonDocument;
// writes a ScenarioDesc and diagnostics. Private to throng_io.
#pragma once
#include <cstdint>
#include <vector>

#include "json_document.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::io {

/// The description plus which of its parts parsed cleanly. Every array element of the JSON is
/// kept (with defaults where a field was bad) so that desc indices equal JSON array indices and
/// "/points/3" names desc.points[3].
struct ParsedScenario {
  sim::ScenarioDesc desc;
  std::vector<bool> walkableOk;    ///< per walkable polygon: a simple polygon with area
  std::vector<bool> obstaclesOk;   ///< per obstacle polygon (the file's, then the walls' footprints)
  std::vector<bool> wallsOk;       ///< per wall: line and thickness valid (its footprints are in desc.obstacles)
  std::vector<bool> measurementsOk;  ///< per measurement line or area
  /// How many of desc.obstacles come from "/obstacles"; the rest are wall footprints.
  std::size_t listedObstacles = 0;
  /// Per wall footprint (desc.obstacles[listedObstacles + k]): the index of its wall in "/walls".
  std::vector<std::uint32_t> obstacleWall;
  bool terrainOk = true;           ///< "terrain" absent, or its vertices and triangles all valid
  std::vector<bool> pointsOk;      ///< per point: region parsed and valid
  std::vector<bool> populationsOk; ///< per population: every field parsed (spawn, goals and follow resolved)
  bool structureOk = false;        ///< no diagnostic at all from the parser
};

/// Largest coordinate magnitude accepted [m]: float positions keep ~1 cm precision up to here.
inline constexpr double kMaxCoordinate = 100000.0;
/// Most triangles a "terrain" may hold (walkable and obstacles together).
inline constexpr std::size_t kMaxTerrainTriangles = 200000;
/// Most agents a scenario may spawn in total (groups × largest group size, summed).
inline constexpr double kMaxAgents = 10000000.0;
/// Most vertices one polygon may have (walkable, obstacle, point region or spawn): checking stays
/// near-linear, but no scenario drawn by hand or exported from a model needs more.
inline constexpr std::size_t kMaxPolygonVertices = 250000;
/// Pairs of edges the self-intersection check of one polygon may test, plus 64 per vertex:
/// polygons up to ~4,000 points are always checked exactly; bigger ones unless hostile.
inline constexpr std::uint64_t kSelfIntersectionTests = 10000000;
/// Most points (and most populations) a file may list: each costs memory and checks (a file of
/// 600,000 points took 1.3 GB); no meaningful scenario comes near.
inline constexpr std::size_t kMaxPoints = 100000;
inline constexpr std::size_t kMaxPopulations = 10000;

/// Most wall segments a file may hold in total: each becomes an obstacle polygon.
inline constexpr std::size_t kMaxWallSegments = 100000;
/// Most measurement lines and areas a file may list.
inline constexpr std::size_t kMaxMeasurements = 10000;
inline constexpr std::size_t kMaxSmoke = 1000;
inline constexpr std::size_t kMaxTransports = 10000;

[[nodiscard]] ParsedScenario parseScenarioJson(const JsonDocument& doc, core::Diagnostics& diagnostics);

/// Removes a closing vertex equal to the first and consecutive duplicates; `original` receives,
/// for each kept vertex, its index in the input.
[[nodiscard]] core::Polygon normalizePolygon(const core::Polygon& poly, std::vector<std::size_t>& original);

/// The obstacles a wall stands for: per segment of its line (consecutive duplicates skipped), a
/// rectangle `thickness` wide lengthened by thickness/2 at both ends, so that the rectangles of two
/// segments meeting at any angle cover the joint (each holds the disc of radius thickness/2 around
/// the shared point). Counter-clockwise; computed in double precision.
[[nodiscard]] std::vector<core::Polygon> wallFootprints(const sim::WallDesc& wall);

/// The JSON pointer of desc.obstacles[k]: "/obstacles/k" for a listed obstacle, "/walls/j" for a
/// wall's footprint.
[[nodiscard]] std::string obstaclePointer(const ParsedScenario& parsed, std::size_t k);

}  // namespace throng::io

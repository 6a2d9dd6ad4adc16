// throng::io scenario validator — the semantic checks that need several parts of a parsed
// scenario at once: spawns inside the walkable area and clear of obstacles, spawn areas large
// enough for their agents, scripted guide waypoints (crowd model) on walkable ground clear of
// obstacles, and (optionally) every goal reachable on the navmesh from its spawn. On a multi-level
// world (ScenarioDesc::terrain) the navmesh is built from the terrain and points, spawns and
// waypoints are checked by snapping to it at their heights (only when reachability is asked for).
// Reads ParsedScenario and the JsonDocument (for positions); writes diagnostics and the navmesh.
// Private to throng_io.
#pragma once
#include <memory>

#include "json_document.hpp"
#include "scenario_parser.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::io {

/// Packing factor for spawn capacity: at most this fraction of a spawn area is covered by bodies
/// (random non-overlapping placement jams near 0.55; 0.5 leaves the spawner room).
inline constexpr double kSpawnPackingFactor = 0.5;

/// Appends one diagnostic per problem. Runs each check only where its inputs parsed cleanly;
/// builds the navmesh (stored in `navmesh`) only when reachability is asked for and nothing else
/// is wrong.
void validateScenario(const JsonDocument& doc, const ParsedScenario& parsed, const LoadOptions& options,
                      core::Diagnostics& diagnostics, std::shared_ptr<const nav::NavMesh>& navmesh);

/// A crowd file's checks (crowd_parser.cpp): `parsed` as ScenarioReader::runCrowd made it. Points
/// before `firstOwnPoint` are the world's (valid already, not checked again; pointers to the
/// crowd's own points count from it). Reachability uses the world's `navmesh` (none: skipped).
void validateCrowd(const JsonDocument& doc, const ParsedScenario& parsed, std::size_t firstOwnPoint,
                   std::shared_ptr<const nav::NavMesh> navmesh, core::Diagnostics& diagnostics);

}  // namespace throng::io

// throng::io crowd loading — a crowd file (JSON "throng-crowd/1": points and populations, see
// docs/scenario-format.md "Crowd files") → sim::CrowdDesc validated against a running world,
// ready for sim::World::insertCrowd. Parsed by the scenario parser's own readers, so it gets the
// same diagnostics (file:line:column, JSON pointer, what was expected, "did you mean"). A bad file
// gives diagnostics only; nothing is inserted.
#pragma once
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"
#include "throng/sim/world.hpp"

namespace throng::io {

struct CrowdOptions {
  /// The world's navmesh: spawns and goals must be reachable on it. None: that check is skipped.
  std::shared_ptr<const nav::NavMesh> navmesh;
  /// Ids in use besides the world description's own: crowds inserted (or queued) before.
  std::vector<std::string> takenCrowdIds, takenPointIds, takenPopulationIds;
};

/// Parses crowd JSON and validates it against `world` (the description the crowd joins): point
/// ids it names must exist in the world or the file, its new ids must be free, spawns inside the
/// walkable area and clear of obstacles with room for their agents, goals reachable from the
/// spawns, body radii within the navmesh's erosion radius, actions among the world's clips, at
/// most sim::kMaxInsertAgents agents. `source` names the text in diagnostics.
core::Result<sim::CrowdDesc> parseCrowd(std::string_view text, const std::string& source, const sim::ScenarioDesc& world,
                                        const CrowdOptions& options = {});

/// parseCrowd against a running world: its description, navmesh and the crowds it has.
core::Result<sim::CrowdDesc> parseCrowd(std::string_view text, const std::string& source, const sim::World& world);

/// Reads the file and calls parseCrowd; an unreadable file is one diagnostic naming it.
core::Result<sim::CrowdDesc> loadCrowdFile(const std::string& path, const sim::ScenarioDesc& world,
                                           const CrowdOptions& options = {});

}  // namespace throng::io

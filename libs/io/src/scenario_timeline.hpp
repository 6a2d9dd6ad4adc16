// throng::io scenario timeline loading — reads the crowd files a scenario's "timeline" inserts
// (scenario_timeline.cpp). Private to throng_io.
#pragma once
#include <memory>

#include "json_document.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::io {

/// Loads every "insert" entry's crowd file (relative to the scenario's directory) against `desc`
/// and its `navmesh` (none: no reachability check) into desc.timeline; checks "remove" entries.
/// Diagnostics of a crowd file point into that file.
void loadScenarioTimeline(const JsonDocument& doc, sim::ScenarioDesc& desc, std::shared_ptr<const nav::NavMesh> navmesh,
                          core::Diagnostics& diagnostics);

}  // namespace throng::io

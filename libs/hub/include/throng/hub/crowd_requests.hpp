// throng::hub crowd requests — a crowd inserted into, or removed from, a running world at a
// client's request (the server's InsertCrowd / RemoveCrowd, the shared-memory link's insert /
// remove requests): the crowd file's text is parsed and validated against the world
// (io::parseCrowd), checked against an agent limit, and queued with World::insertCrowd; a bad file
// changes nothing and the outcome carries its diagnostics (file:line:column, JSON pointer, what
// was expected). Reads the world, writes its crowd queue. Call between ticks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "throng/core/diagnostic.hpp"
#include "throng/sim/world.hpp"

namespace throng::hub {

/// What became of one insertion or removal.
struct CrowdOutcome {
  bool ok = false;
  std::uint32_t index = 0;      ///< the crowd's index in insertion order (ok, or a removal of a known crowd)
  std::string id;               ///< the crowd's id (empty when the file could not be read that far)
  std::uint64_t maxAgents = 0;  ///< insertion: agents the crowd may hold at once
  bool tooLarge = false;        ///< refused for an agent limit (per request or over the whole run)
  core::Diagnostics diagnostics;  ///< why it was refused (empty when ok)
  std::string text;             ///< one line saying what happened (ok), or the first diagnostic
};

/// Parses `json` (a "throng-crowd/1" file; `source` names it in diagnostics) against `world`,
/// refuses more than `maxAgents` agents (at most sim::kMaxInsertAgents apply anyway), and queues
/// it: its agents appear at the start of the next tick.
CrowdOutcome insertCrowdJson(sim::World& world, std::string_view json, const std::string& source,
                             std::uint64_t maxAgents = sim::kMaxInsertAgents);

/// Queues the removal of crowd `id` (its agents leave at the next tick); not ok when no crowd
/// has that id or it was removed already.
CrowdOutcome removeCrowdById(sim::World& world, std::string_view id);

/// The diagnostics one per line, cut to at most `maxBytes` bytes at a line boundary with
/// "(and N more)" saying how many were left out.
std::string diagnosticsText(const core::Diagnostics& diagnostics, std::size_t maxBytes);

/// True when a diagnostic is about an agent limit ("... agents per ...", "at most N agents").
bool isAgentLimit(const core::Diagnostics& diagnostics);

}  // namespace throng::hub

// throng::hub crowd requests — a crowd inserted into, or removed from, a running world at a
// client's request (the server's InsertCrowd / RemoveCrowd, the shared-memory link's insert /
// remove requests). An insertion is checked against per-request limits (size, nesting, keys,
// values, vertices: checkCrowdLimits, one linear pass), parsed and validated against the world
// (io::parseCrowd), checked against an agent limit, and queued with World::insertCrowd; a bad file
// changes nothing and the outcome carries its diagnostics (file:line:column, JSON pointer, what
// was expected). The parsing and validation (parseCrowdRequest) need only a copy of the world's
// description, so a server runs them off the simulation thread and queues the result between
// ticks (queueCrowd). Removal is by id, and only by the crowd's owner where owners are kept
// (CrowdOwners). Reads the world, writes its crowd queue.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "throng/core/diagnostic.hpp"
#include "throng/core/result.hpp"
#include "throng/io/crowd_loader.hpp"
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

/// Bounds on one crowd request's text, checked in one pass before it is parsed, so that no request
/// can make the parser or the validator work for long (docs/server.md "Crowds inserted at run time").
struct CrowdLimits {
  std::size_t maxBytes = 1u << 20;       ///< the text [bytes] (protocol::kMaxCrowdJson)
  std::size_t maxDepth = 16;             ///< nesting of arrays and objects (a crowd file needs about 7)
  std::size_t maxKeys = 10000;           ///< object keys, all objects together
  std::size_t maxValues = 100000;        ///< values (numbers, strings, arrays, objects...), all together
  std::size_t maxPolygonVertices = 1000; ///< positions ([x, y] or [x, y, z]) in one array (a polygon)
  std::size_t maxVertices = 10000;       ///< positions in the whole request
};

/// One diagnostic naming the first limit `json` exceeds (source:line:column, the JSON pointer where
/// it was crossed, the limit), or one naming its first byte that is not UTF-8; empty when it keeps
/// within every limit. Linear in the text; not a JSON validator (io::parseCrowd reports syntax).
core::Diagnostics checkCrowdLimits(std::string_view json, const std::string& source, const CrowdLimits& limits = {});

/// A crowd request parsed and validated, ready for queueCrowd, or why not.
struct ParsedCrowd {
  std::optional<sim::CrowdDesc> crowd;  ///< set when it may be queued
  CrowdOutcome refusal;                 ///< otherwise: why not (its `id` filled when the file got that far)
};

/// checkCrowdLimits, then io::parseCrowd against `world` (a world description; its navmesh and
/// crowd ids in `options`), then at most `maxAgents` agents. Needs no World: may run on any thread.
ParsedCrowd parseCrowdRequest(std::string_view json, const std::string& source, const sim::ScenarioDesc& world,
                              const io::CrowdOptions& options, std::uint64_t maxAgents, const CrowdLimits& limits = {});

/// Queues a parsed crowd with World::insertCrowd (which checks its ids against the crowds queued
/// since it was parsed): its agents appear at the start of the next tick.
CrowdOutcome queueCrowd(sim::World& world, const sim::CrowdDesc& crowd);

/// Parses `json` (a "throng-crowd/1" file; `source` names it in diagnostics) against `world`,
/// within `limits`, refuses more than `maxAgents` agents (at most sim::kMaxInsertAgents apply
/// anyway), and queues it: parseCrowdRequest and queueCrowd on the calling thread.
CrowdOutcome insertCrowdJson(sim::World& world, std::string_view json, const std::string& source,
                             std::uint64_t maxAgents = sim::kMaxInsertAgents, const CrowdLimits& limits = {});

/// Who inserted each crowd at a client's request: a crowd belongs to whoever inserted it, the
/// crowds of the scenario (its timeline) to the scenario; only the owner removes it.
class CrowdOwners {
 public:
  /// Crowd `id` was inserted by participant `participant` (`name` for the refusals' texts).
  void add(const std::string& id, std::uint32_t participant, const std::string& name);
  /// The participant that inserted crowd `id`; nothing for the scenario's crowds.
  [[nodiscard]] std::optional<std::uint32_t> owner(std::string_view id) const;
  /// Why `participant` may not remove crowd `id` (a diagnostic naming the owner), or nothing.
  [[nodiscard]] std::optional<core::Diagnostic> refusal(std::string_view id, std::uint32_t participant) const;
  [[nodiscard]] const std::map<std::string, std::pair<std::uint32_t, std::string>, std::less<>>& all() const {
    return owners_;
  }

 private:
  std::map<std::string, std::pair<std::uint32_t, std::string>, std::less<>> owners_;  ///< id → participant, name
};

/// Queues the removal of crowd `id` (its agents leave at the next tick); not ok when no crowd
/// has that id or it was removed already, or — with `owners` — when `participant` does not own it.
CrowdOutcome removeCrowdById(sim::World& world, std::string_view id, const CrowdOwners* owners = nullptr,
                             std::uint32_t participant = 0);

/// The diagnostics one per line, cut to at most `maxBytes` bytes at a line boundary with
/// "(and N more)" saying how many were left out.
std::string diagnosticsText(const core::Diagnostics& diagnostics, std::size_t maxBytes);

/// True when a diagnostic is about an agent limit ("... agents per ...", "at most N agents").
bool isAgentLimit(const core::Diagnostics& diagnostics);

}  // namespace throng::hub

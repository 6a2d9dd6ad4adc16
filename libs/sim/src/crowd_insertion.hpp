// CrowdInsertion — crowds inserted and removed at run time (World::insertCrowd, removeCrowd and the
// scenario's timeline): each crowd's description until it is applied, its ids and what it added,
// the commands queued for the next tick (exits closed and opened by World::setExitOpen too), the timeline's progress, and the budget of agents all
// insertions may add. Written by insert.cpp only (serial, at the start of a tick).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "throng/sim/world.hpp"

namespace throng::sim {

/// An inserted crowd (insert.cpp): queued by World::insertCrowd or the timeline, applied at the
/// start of a tick, maybe removed later.
struct CrowdState {
  CrowdDesc desc;                  ///< kept until applied, then cleared (its parts live in World::Impl::desc)
  CrowdInfo info;
  std::vector<std::string> pointIds, populationIds;  ///< taken ids (clash checks, also while queued)
};

/// A crowd command, applied in order at the start of the next tick.
struct CrowdCommand {
  std::uint32_t crowd = 0;  ///< index into CrowdInsertion::crowds
  bool insert = true;       ///< false = remove
};

struct CrowdInsertion {
  std::vector<CrowdState> crowds;
  std::vector<CrowdCommand> commands;       ///< applied in order at the start of the next tick
  /// World::setExitOpen's (exit point, closed) pairs, applied in order after the crowd commands.
  std::vector<std::pair<std::uint32_t, bool>> exitCommands;
  std::vector<std::uint64_t> timelineTick;  ///< per ScenarioDesc::timeline entry: the tick it applies at
  std::size_t timelineNext = 0;             ///< first timeline entry not applied yet
  std::uint64_t insertedAgents = 0;         ///< most agents all insertions may add (kMaxInsertedAgents)
  float navRadius = 0.0f;                   ///< the navmesh's erosion radius (the scenario's largest body) [m]
};

}  // namespace throng::sim

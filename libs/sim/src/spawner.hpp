// Spawner — when and how many agents enter the world, and the spawn phase that lets them in.
// The Spawner (spawner.cpp) owns, per population, the tick it starts, whether it has spawned, its
// group sizes (drawn per stable group id) and its first group id; the next stable agent id; and
// the spawn events since the last frame taken, kept compactly. Its registerGroups, shared by
// creation (World::create) and run-time insertion (insert.cpp), registers a population's groups.
// The spawn phase (spawnDue: SpawnInput, SpawnOutput; spawn.cpp) places the populations due this
// tick (spawn_layout.hpp) and gives their agents rows, speeds, interests, groups, first goals and
// pre-movement times (preMovementTime).
// Serial code only: spawning runs at the start of a tick (World::Impl::applyCommands).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "agent_store.hpp"
#include "common_ground_state.hpp"
#include "exit_choice.hpp"
#include "goals.hpp"
#include "group_table.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {

class Spawner {
 public:
  // ---- the schedule (one entry per population, in population order)

  /// Schedules the next population (index populations()) to start at `startTick`.
  void addPopulation(std::uint64_t startTick);
  [[nodiscard]] std::size_t populations() const { return startTick_.size(); }
  /// Populations not spawned yet whose start tick is `tick` or earlier, ascending.
  [[nodiscard]] std::vector<std::size_t> due(std::uint64_t tick) const;
  [[nodiscard]] bool spawned(std::size_t population) const { return spawned_[population] != 0; }
  /// Whether every population has spawned (or was cancelled).
  [[nodiscard]] bool allSpawned() const;
  void markSpawned(std::size_t population) { spawned_[population] = 1; }
  /// The population spawns nobody any more (its crowd was removed). Returns the agents it would
  /// still have spawned: 0 when it had spawned already.
  std::uint32_t cancel(std::size_t population);

  // ---- groups and ids

  /// Registers the groups of populations [firstPopulation, desc.populations.size()) — creation
  /// and run-time insertion alike, so a group is the same whichever way its population came: their
  /// sizes (drawn per stable group id), first group ids, goal lists (one per population, appended
  /// to `goalLists`), the groups themselves with the busy set, routes (following, guide scripts)
  /// and cold parts. Every population must have been scheduled (addPopulation) and the earlier
  /// ones registered. Returns the agents its groups will spawn.
  std::uint32_t registerGroups(const ScenarioDesc& desc, std::uint32_t firstPopulation, GroupTable& groups,
                               std::vector<std::vector<std::uint32_t>>& goalLists);
  /// The population's group sizes, in group id order (registered populations only).
  [[nodiscard]] std::span<const std::uint32_t> groupSizes(std::size_t population) const { return groupSizes_[population]; }
  /// The agents the population spawns (its group sizes summed).
  [[nodiscard]] std::uint32_t agentsOf(std::size_t population) const;
  /// The stable id of the population's first group; its groups follow in order.
  [[nodiscard]] std::uint32_t firstGroupId(std::size_t population) const { return firstGroupId_[population]; }
  /// Stable agent ids handed out so far: the next agent gets this one.
  [[nodiscard]] std::uint32_t nextAgentId() const { return nextAgentId_; }
  /// Hands out the next stable agent id.
  std::uint32_t takeAgentId() { return nextAgentId_++; }

  // ---- spawn events (24 bytes per agent otherwise, for a million agents entering at once)

  /// Agent `agent`, member `member` of group `group` of `population`, entered at `tick`; its event
  /// belongs before events[at] of the world's pending events.
  void recordSpawn(std::size_t at, std::uint64_t tick, std::uint32_t population, std::uint32_t agent,
                   std::uint32_t group, std::uint32_t member);
  /// The pending events with the spawn events written out in place, as if each had been stored;
  /// empties `pending` and the recorded runs.
  [[nodiscard]] std::vector<Event> takeEvents(std::vector<Event>& pending);

 private:
  /// `count` agents with consecutive ids from `firstAgent` (the first one member `member` of group
  /// `group`, then in group order) entered at `tick`; their events belong before pending[at].
  struct SpawnRun {
    std::size_t at = 0;
    std::uint64_t tick = 0;
    std::uint32_t population = 0, firstAgent = 0, count = 0, group = 0, member = 0;
  };
  /// registerGroups' steps. The sizes drawn: agents scheduled, the end of the groups' ids and
  /// the cold parts they may need (at most one per busy group; a follower and the group it
  /// follows: two).
  struct DrawnSizes {
    std::uint32_t scheduled = 0, groupEnd = 0;
    std::size_t extras = 0;
  };
  DrawnSizes drawGroupSizes(const ScenarioDesc& desc, std::uint32_t firstPopulation, std::uint32_t firstGroup);
  void addGroups(const ScenarioDesc& desc, std::uint32_t firstPopulation, GroupTable& groups,
                 std::vector<std::vector<std::uint32_t>>& goalLists);
  void markBusyAndRoutes(const ScenarioDesc& desc, std::uint32_t firstGroup, GroupTable& groups) const;
  /// Writes out one run's events.
  void expand(const SpawnRun& run, std::vector<Event>& out) const;

  std::vector<std::uint64_t> startTick_;
  std::vector<std::uint8_t> spawned_;
  std::vector<std::vector<std::uint32_t>> groupSizes_;
  std::vector<std::uint32_t> firstGroupId_;
  std::uint32_t nextAgentId_ = 0;
  std::vector<SpawnRun> runs_;
};

// ---- the spawn phase (spawn.cpp): the populations due this tick enter the world.

struct SpawnInput {
  /// seed, populations (spawn area, group sizes, speeds, radius, interests, automatic goals),
  /// points (spawn points' floors), maxRadius (the occupancy grid's cell)
  const ScenarioDesc& desc;
  const nav::NavQuery& query;             ///< the main (serial) query: spots on the navmesh, floor heights
  std::uint64_t tick;
  const CommonGroundState& commonGround;  ///< interest categories (Common Ground on)
};

struct SpawnOutput {
  Spawner& spawner;    ///< populations marked spawned, agent ids handed out, spawn events recorded
  /// Rows appended for the new agents, every column of theirs written (existing rows: positions
  /// and radii read, to keep new bodies clear of them).
  AgentStore& agents;
  GroupTable& groups;  ///< the new agents join their groups (members, leader)
  /// First goals of the new agents (automatic goals: a group's own list); its event list is the
  /// world's pending events, before whose end spawn events are recorded.
  GoalWriter& goals;
  WorldStats& stats;   ///< spawned, scheduled, active
  /// Exit choice: a group of a population with "exits" chooses its first exit where it spawns
  /// (and gets a goal list of its own); null: no population chooses.
  ExitChoice* exits = nullptr;
};

/// Spawns populations `due` (ascending, as Spawner::due gives them), in order: random free spots
/// in each spawn area; when that fails for some population, the populations whose areas overlap it
/// are laid out again on a packed lattice inside their areas (deterministic, never off the area
/// while it has room). Each agent then gets the next stable id, a row, a desired speed (drawn
/// per stable id; a flocking group's shared speed), Common Ground interests, its group and the
/// group's current goal. With a pre-movement time (PopulationDesc::preMovement) an agent heading
/// for a goal stands (GoalState::PreMovement, mode Waiting) until the tick its time ends
/// (actionEndTick); its path is planned meanwhile.
void spawnDue(const SpawnInput& in, const SpawnOutput& out, std::span<const std::size_t> due);

/// Agent `agentId`'s pre-movement time [s], drawn from (seed, stable id, RngPurpose::PreMovement)
/// — the same for any thread or rank count —; normal and log-normal draws are clamped to
/// [0, kMaxPreMovement]. 0 without a distribution.
[[nodiscard]] double preMovementTime(const PreMovementDesc& d, std::uint64_t seed, std::uint32_t agentId);

}  // namespace throng::sim

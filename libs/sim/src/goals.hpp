// goals — writing where agents are going (goals.cpp). What writing goals needs is named here:
// PointRegions (the points' regions cut into sub-regions, and how many agents target each) is
// owned by World::Impl; GoalWriter references it with the goal lists, the group table, the agent
// columns it writes and the main navmesh query, and holds the operations that change an agent's
// goal: setGoal / advanceGoal, drawTarget / releaseTarget, bezierPath, reconstructGoals and
// applyPendingGoals, and the waypoint choices (OpenChoices) made when a group reaches them. Serial code only (the group pass, spawning, run-time insertion): occupancy
// and goal lists are shared. Reading goals is GoalView (phases.hpp), which the parallel phases use.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "agent_store.hpp"
#include "group_table.hpp"
#include "phases.hpp"
#include "throng/core/geometry.hpp"
#include "throng/crowd/subregions.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

class VerticalTransports;
class TransportRoutes;

/// Every point's bounds and sub-regions (Musse et al. §3.1.3), flattened: point p owns
/// [subOffset[p], subOffset[p + 1]); occupancy = agents whose current target lies in it.
struct PointRegions {
  std::vector<core::Aabb> bounds;
  std::vector<crowd::Subregion> subregions;
  std::vector<std::uint32_t> subOffset{0};
  std::vector<std::uint32_t> occupancy;

  /// A point's bounds and sub-regions, with no one targeting them yet (creation and insertion).
  void add(const PointDesc& p);
};

/// Waypoint choices not made yet (PopulationDesc::goalChoices), per goal list: the group whose
/// own list it is, and per slot 1 + the index of its population's choice there (0: a plain goal,
/// or one chosen already). Lists without choices have no entry (or an empty one).
struct OpenChoices {
  struct List {
    std::uint32_t group = 0;
    std::vector<std::uint32_t> choiceAt;
  };
  std::vector<List> lists;  ///< indexed by goal list
};

/// How a target is picked inside a point of this kind (crowd::pickSubregion): an exit's near side
/// (the default detour limit), the whole region of an interest or action point.
[[nodiscard]] crowd::PickParams pickParams(PointKind kind);

/// Writes goals (serial). Built by World::Impl::goalWriter() where goals change; references only.
struct GoalWriter {
  const ScenarioDesc& desc;   ///< seed, points, populations (wander, bezierPaths, autoNearDistance)
  GroupTable& groups;         ///< a group's goal list, cursor and flocking; reconstructGoals sets goalList
  std::vector<std::vector<std::uint32_t>>& goalLists;  ///< reconstructGoals appends a group's own list
  PointRegions& regions;      ///< sub-region occupancy (drawTarget, releaseTarget; least-targeted choices)
  OpenChoices& choices;       ///< waypoint choices still to make (openGoalChoices, setGoal)
  /// Reads id, group, posX/Y/Z; writes goalCursor, goalState, mode, targetX/Y/Z, targetSub,
  /// targetDraws, needPath, ticket, corners, dynamicTarget, progressDistance, goalPending.
  AgentStore& agents;
  const nav::NavQuery& query; ///< the main (serial) navmesh query
  std::uint64_t tick;
  std::vector<Event>& events; ///< PathFallback, ExitChosen, WaypointChosen
  /// Choosing lifts and escalators (transport_choice.hpp): null where the world has none.
  TransportRoutes* routes = nullptr;
  const VerticalTransports* transports = nullptr;

  [[nodiscard]] GoalView view() const { return {groups, goalLists, agents.group, agents.goalCursor}; }
  /// Chooses a target inside the point's region (on the navmesh) for agent `row`: in a sub-region
  /// picked by proximity and occupancy (pickParams), which it then occupies (the old one is released).
  /// i's target spot in `point`'s region (sub-regions, or its lane: PointDesc::aim), snapped onto
  /// the mesh. `from`: the goal i reached last (a lane runs from its centre), null for none.
  core::Vec2 drawTarget(std::size_t row, const PointDesc& point, const PointDesc* from = nullptr);
  /// Releases the sub-region `row` was targeting (its occupancy drops).
  void releaseTarget(std::size_t row);
  /// Points `row` at goal `cursor` of its group's active goal list (or wandering / Done past it).
  void setGoal(std::size_t row, std::uint32_t cursor);
  /// When `row`'s group has not decided yet how to reach the goal at `cursor` (no transport's stop)
  /// and riding a lift or escalator is quicker than walking (TransportRoutes::boardingFor), puts the
  /// boarding stop before that goal in the group's own goal list (a copy of its list, the first
  /// time); a WaypointChosen event names the stop.
  void routeByTransport(std::size_t row, std::uint32_t cursor);
  /// Moves `row` on to its next goal (or wandering, or Done).
  void advanceGoal(std::size_t row) { setGoal(row, agents.goalCursor[row] + 1); }
  /// Replaces the navmesh request of `row` by a Bézier path when one fits (PathFallback otherwise).
  void bezierPath(std::size_t row);
  /// Automatic goals for group `gid` spawning around `anchor` (a new goal list of its own).
  void reconstructGoals(std::uint32_t gid, core::Vec2 anchor);
  /// Exit choice (exit_choice.hpp): gives group `gid` a goal list of its own, its population's
  /// goals and then `exit`.
  void giveExitGoals(std::uint32_t gid, std::uint32_t exit);
  /// Waypoint choices: when group `gid`'s population has goal choices, gives the group a goal list
  /// of its own (unless it has one: exits) whose choice slots setGoal fills in, once, when the
  /// group's first member reaches each (chooseWaypoint).
  void openGoalChoices(std::uint32_t gid);
  /// Fills in the choice at `cursor` of `row`'s active goal list if it is still open: by shares
  /// (one draw from the list owner's stream) or the option fewest agents target now (sub-region
  /// occupancy), for the whole group; a WaypointChosen event names the group's leader.
  void chooseWaypoint(std::size_t row, std::uint32_t cursor);
  /// Changes group `gid`'s exit (the last entry of its own list) to `exit`: members walking to the
  /// exit get a target in the new one (standing ones before their pre-movement time ends keep
  /// standing); an ExitChosen event names `agentId` (the member who decided).
  void changeExit(std::uint32_t gid, std::uint32_t exit, std::span<const std::uint32_t> rowOfId, std::uint32_t agentId);
  /// Applies the goal changes decide asked for (AgentStore::goalPending), in row order: the rows
  /// the chunks list, whose lists it clears.
  void applyPendingGoals(std::span<ChunkOutput> chunks);
};

}  // namespace throng::sim

// World::Impl — the world's state and its phases. Each phase lives in its own file:
//   spawn.cpp      applyCommands: populations due this tick enter the world
//   sense.cpp      grid rebuild and k-nearest neighbours
//   decide.cpp     goal logic: regions reached, actions, exits, new targets
//   plan.cpp       budgeted path planning through nav::PathQueue
//   steer.cpp      preferred velocity along the path, then ORCA
//   integrate.cpp  commit velocities, move along the navmesh, headings, statistics
//   world.cpp      the tick, emit (removal, frame), creation
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "agent_store.hpp"
#include "spatial_grid.hpp"
#include "walls.hpp"
#include "throng/core/rng.hpp"
#include "throng/crowd/subregions.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"
#include "throng/sim/orca.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {

/// Margin kept between agent centres and the eroded navmesh boundary by ORCA [m].
inline constexpr float kWallMargin = 0.01f;
/// Detour node expansions the plan phase may spend per tick (time-slicing, as dtPathQueue).
inline constexpr int kPathIterationsPerTick = 20000;
/// Period of the progress check that triggers a re-plan for an agent that is stuck [s].
inline constexpr float kProgressCheckPeriod = 4.0f;

/// One social group (Musse et al. §3.1.2: a crowd is a set of groups). Cold data, indexed by the
/// stable group id; written only by the serial group pass (groups.cpp) and by spawning.
struct GroupState {
  std::uint16_t population = 0;
  std::vector<std::uint32_t> members;  ///< stable ids present in the world, ascending
  std::uint32_t expected = 0;          ///< members that will be spawned
  std::uint32_t leader = kNoAgent;
  std::uint32_t goalList = 0;          ///< own goal list: index into World::Impl::goalLists
  std::uint32_t cursor = 0;            ///< goal the group is heading for (index into the active list)
  float speed = 1.34f;                 ///< shared walking speed when flocking [m/s]
  // Waiting (flocking rule 4).
  bool waiting = false;
  std::uint64_t waitStart = 0;
  // Formation.
  core::Vec2 centroid, heading{1.0f, 0.0f};
  // Following (§3.2.5).
  std::uint32_t followGroup = kNoAgent;  ///< group followed while `following`
  bool following = false;
  std::uint64_t followToggle = 0;        ///< tick the current (temporary) period ends
  std::uint32_t ownCursor = 0;           ///< own cursor saved while following temporarily
  // Guidance (§3.2.6).
  bool guided = false;
  bool guidedByApi = false;
  core::Vec2 guide;
  core::Vec2 guidePlanned{1e30f, 1e30f};  ///< guide position the members' paths were planned for
  // Common Ground (social.cpp).
  std::uint32_t coordination = kNoAgent;  ///< id of the coordination its members play now
  std::uint32_t reunite = kNoAgent;       ///< a divide ended: id of that coordination until the group is whole again

  [[nodiscard]] bool flocks(const PopulationDesc& pop) const { return pop.flocking && expected >= 2; }
};

/// One Common Ground interaction being carried out (or a lone visit): the planned action script
/// and where each actor is in it. Times of entries not yet started shift by `slip`, the overrun of
/// walks that took longer than planned (paths bend, crowds slow), so every response still starts
/// after the motion it answers.
struct ActiveCoordination {
  CoordinationRecord record;            ///< filled as it goes; published when it ends
  std::vector<std::uint32_t> actors;    ///< stable ids: [0] A, [1] B, then companions
  social::ActionScript script;
  std::vector<std::uint32_t> cursor;    ///< per actor: entry being played (== size: done)
  std::vector<double> started;          ///< per actor: actual start of the current entry, < 0 not started
  std::vector<std::uint8_t> left;       ///< per actor: has left the script (resumed or gone)
  double slip = 0.0;                    ///< [s]
  double deadline = 0.0;                ///< [s] every actor is released by then, whatever happened
  bool divides = false;                 ///< a divide plan: the group waits to be whole again
  bool reunitedOnReturn = false;        ///< divide-and-wait: A walked back to B
};

/// A command from the World API, applied in order at the start of the next tick.
struct GroupCommand {
  std::uint32_t group = 0;
  bool guide = false;  ///< false = release
  core::Vec2 position;
};

/// Per-worker scratch: navmesh queries and buffers reused across agents (never shared by threads).
struct WorkerScratch {
  std::unique_ptr<nav::NavQuery> query;
  std::vector<OrcaLine> lines;
  std::vector<OrcaLine> projected;
  std::vector<std::uint32_t> wallIds;
  std::vector<std::pair<float, std::uint32_t>> order, line;  // formation
  std::vector<std::pair<float, std::uint32_t>> candidates;
};

/// Per-chunk outputs merged in chunk order (deterministic for any thread count).
struct ChunkOutput {
  std::vector<Event> events;
  double walkedDistance = 0.0;
  double walkingTime = 0.0;
  std::uint64_t socialMeetings = 0;
  std::vector<std::uint32_t> pendingRows;  ///< rows whose goalPending was set, ascending
  std::vector<std::uint32_t> desireRows;   ///< rows whose desirePoint was set (goal generator), ascending
};

struct World::Impl {
  ScenarioDesc desc;
  std::shared_ptr<const nav::NavMesh> navmesh;
  std::unique_ptr<nav::PathQueue> pathQueue;
  std::unique_ptr<nav::NavQuery> mainQuery;  // serial phases
  Walls walls;
  SpatialGrid grid;
  AgentStore agents;
  WorldStats stats;
  std::uint64_t tick = 0;

  // Spawning.
  std::vector<std::uint64_t> populationStartTick;
  std::vector<std::uint8_t> populationSpawned;
  std::vector<std::vector<std::uint32_t>> groupSizes;  // per population, drawn at creation
  std::vector<std::uint32_t> firstGroupId;             // per population
  std::uint32_t nextAgentId = 0;
  std::uint32_t nextGroupId = 0;

  // Groups.
  std::vector<GroupState> groups;
  /// Goal lists (point indices): one per population first, then one per automatic-goals group.
  std::vector<std::vector<std::uint32_t>> goalLists;
  core::SlotMap<GroupTag> groupSlots;       ///< handle → stable group id
  std::vector<GroupId> groupHandles;        ///< stable group id → handle
  std::vector<GroupCommand> commands;
  /// Groups the group pass visits every tick: flocking groups of 2+, guided, following or followed,
  /// or sociable ones. Lone agents with none of these need no per-tick group work.
  std::vector<std::uint8_t> groupBusy;
  std::vector<std::uint32_t> busyGroups;  ///< ascending
  bool busyDirty = true;
  void markBusy(std::uint32_t gid) {
    if (!groupBusy[gid]) { groupBusy[gid] = 1; busyDirty = true; }
  }
  std::vector<core::Vec2> viewers;
  std::vector<std::uint32_t> rowOfId;       ///< stable id → row (kNoAgent if gone), rebuilt when rows change
  bool rowsChanged = true;                  ///< set by spawning and by removals
  bool anySocial = false;                   ///< some population has the sociological model on
  std::vector<std::uint32_t> followingRows; ///< rows following another agent (sociological), ascending

  // Per-point cached geometry and action clips.
  std::vector<core::Aabb> pointBounds;
  std::vector<std::uint16_t> pointClip;
  // Sub-regions of every point's region (Musse et al. §3.1.3), flattened: point p owns
  // [subOffset[p], subOffset[p + 1]); occupancy = agents whose current target lies in it.
  std::vector<crowd::Subregion> subregions;
  std::vector<std::uint32_t> subOffset;
  std::vector<std::uint32_t> subOccupancy;

  // Common Ground (social.cpp).
  std::vector<std::string> categories;        ///< distinct point categories, in point order
  std::vector<std::int32_t> pointCategory;    ///< per point: index into categories, -1 none
  std::vector<std::vector<std::uint32_t>> categoryPoints;  ///< per category: its points
  std::vector<std::uint32_t> attractionPoints;///< points with a category some population is interested in
  std::vector<float> clipDuration;            ///< per animation clip (animationClips) [s]
  std::map<std::string, std::uint16_t, std::less<>> clipIndex;  ///< animation clip name → index
  std::map<std::uint32_t, ActiveCoordination> coordinations;    ///< active, by id (start order)
  std::uint32_t nextCoordinationId = 0;
  std::vector<ScriptRecord> pendingScript;            ///< since the last snapshot
  std::vector<CoordinationRecord> pendingCoordinations;
  void initSocial();
  /// Goal generator for one agent (parallel, in decide): may set desirePoint and list the row.
  void generateGoal(std::size_t row, ChunkOutput& out, const nav::NavQuery& query);
  void startCoordinations();    ///< group pass: desires → coordinations (planner) or lone visits
  void runCoordinations();      ///< group pass: plays every active script one tick
  void beginEntry(ActiveCoordination& c, std::size_t actor, std::size_t row, double now);
  void finishCoordination(ActiveCoordination& c, double now);
  void checkReunions();

  // Threads.
  mutable std::vector<WorkerScratch> scratch;
  std::vector<ChunkOutput> chunks;
  std::vector<Event> pendingEvents;  // since the last snapshot

  // Phases.
  void planPopulations();
  void applyCommands();
  void spawnPopulation(std::size_t populationIndex);
  void sense(const core::TaskSystem& tasks);
  void decide(const core::TaskSystem& tasks);
  void decideGroups(const core::TaskSystem& tasks);  ///< group pass (groups.cpp), after the per-agent part of decide
  void plan();
  void steer(const core::TaskSystem& tasks);
  void integrate(const core::TaskSystem& tasks);
  void emit();

  // Helpers shared by phases.
  WorkerScratch& worker(const core::TaskSystem& tasks);
  void ensureScratch(const core::TaskSystem& tasks);
  [[nodiscard]] bool insideRegion(const PointDesc& point, float x, float y) const;
  /// Chooses a target inside the point's region (on the navmesh) for agent `row`.
  core::Vec2 drawTarget(std::size_t row, const PointDesc& point, const nav::NavQuery& query);
  /// Moves `row` on to its next goal (or wandering, or Done).
  void advanceGoal(std::size_t row, const nav::NavQuery& query);
  /// Points `row` at goal `cursor` of its group's active goal list (or wandering / Done past it).
  void setGoal(std::size_t row, std::uint32_t cursor, const nav::NavQuery& query);
  /// The goal list a group follows now: its own, or the followed group's while following.
  [[nodiscard]] const std::vector<std::uint32_t>& activeGoals(const GroupState& g) const {
    return goalLists[g.following && g.followGroup != kNoAgent ? groups[g.followGroup].goalList : g.goalList];
  }
  // Group pass steps (groups.cpp).
  void applyPendingGoals();
  /// Releases the sub-region `row` was targeting (its occupancy drops).
  void releaseTarget(std::size_t row);
  /// Replaces the navmesh request of `row` by a Bézier path when its population asks for one.
  void bezierPath(std::size_t row, const nav::NavQuery& query);
  /// Automatic goals for a group spawning around `anchor` (groups.cpp).
  void reconstructGoals(std::uint32_t group, core::Vec2 anchor);
  void applyGroupCommands();
  void updateGroupShapes(const core::TaskSystem& tasks);
  void shapeGroup(GroupState& g, WorkerScratch& ws);
  void updateWaiting();
  void updateFollowing();
  void updateGuidance();
  void applySocialEffects();
  void updateLeaders();
  [[nodiscard]] float dt() const { return desc.dt; }
  [[nodiscard]] std::size_t grainFor(std::size_t n) const { return n < 4096 ? 256 : 1024; }
};

}  // namespace throng::sim

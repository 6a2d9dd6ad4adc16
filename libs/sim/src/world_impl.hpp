// World::Impl — the world's state and its phases. Spawning, sense, decide, plan, steer, integrate
// and emit are free functions of their contexts (spawner.hpp, phases.hpp), which Impl builds from
// its state (world.cpp), and so are the group pass's steps (group_pass.hpp, phases.hpp; built in
// decideGroups); goals are written through a GoalWriter (goals.hpp, goalWriter()). The owned parts:
// the Spawner (spawner.hpp), the GroupTable (group_table.hpp), the Common Ground state
// (common_ground_state.hpp), the crowd insertion (crowd_insertion.hpp), the partition (below). What
// is left as Impl's methods: building the contexts, creation, run-time crowd insertion (it edits
// the scenario itself), the group pass's order, the models in use and the partition's exchange.
// Where things live:
//   spawner.cpp    the Spawner: schedule, registerGroups (creation and insertion), ids, spawn events
//   spawn.cpp      spawnDue: populations due this tick enter the world (spawn_layout.cpp: where)
//   insert.cpp     crowds inserted and removed at run time (API and scenario timeline), agents removed by id
//   sense.cpp      grid rebuild and k-nearest neighbours
//   decide.cpp     goal logic: regions reached, actions, exits, progress checks, meetings
//   groups.cpp     the group pass after decide (commands, guidance, following, waiting, formation)
//   common_ground.cpp, common_ground_play.cpp  the Common Ground model (goals, coordinations, scripts)
//   plan.cpp       budgeted path planning through nav::PathQueue
//   exit_choice.cpp  exit choice: distance fields, queues, re-evaluation (the tactical layer)
//   goals.cpp      one home for goals: active list, current point; GoalWriter (goals.hpp): set/advance,
//                  targets and sub-regions, Bézier paths, automatic goals, pending goal changes
//   steer.cpp      preferred velocity along the path, then the population's avoidance model
//   models/        the avoidance models behind OperationalModel (ORCA, collision-free speed, …)
//   integrate.cpp  commit velocities, move along the navmesh, headings, statistics
//   vertical_transport.cpp  lifts and escalators: queues, cars and belts, people let off (after integrate)
//   emit.cpp       emit (chunks merged, agents that exited removed, the clock) and takeFrame
//   world.cpp      creation, the tick, the phases' contexts, the models in use, the World API
#pragma once
#include <array>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "agent_store.hpp"
#include "common_ground_state.hpp"
#include "crowd_insertion.hpp"
#include "exit_choice.hpp"
#include "goals.hpp"
#include "group_pass.hpp"
#include "group_table.hpp"
#include "spawner.hpp"
#include "transport_choice.hpp"
#include "vertical_transport.hpp"
#include "throng/core/assert.hpp"
#include "throng/sim/spatial_grid.hpp"
#include "walls.hpp"
#include "throng/core/rng.hpp"
#include "throng/crowd/subregions.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"
#include "models/operational_model.hpp"
#include "phases.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {

/// The steer phase shared with other ranks (partition.hpp, partition.cpp). Unset (exchange ==
/// nullptr), none of this is touched and steer visits every row as always.
struct PartitionState {
  StepExchange* exchange = nullptr;
  PartitionOptions options;
  PartitionStats stats;
  std::vector<float> cuts;                   ///< ranks - 1 strip cuts in x, ascending [m]
  std::vector<std::uint16_t> ownerOfId;      ///< rank that steered each stable id last tick, 0xffff: none yet
  std::vector<std::uint16_t> rowOwner;       ///< this tick's owner of every row
  std::vector<std::uint32_t> ownedRows;      ///< rows this rank steers this tick, ascending
  std::vector<std::byte> steerSend, steerGathered;
  std::vector<std::size_t> steerSizes;
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

  // Spawning (spawner.hpp: the schedule, group sizes, id counters, compact spawn events).
  Spawner spawner;

  // Groups (group_table.hpp): groups, their cold parts and routes, the busy set.
  GroupTable groups;
  /// Goal lists (point indices): one per population first, then one per automatic-goals group (goals.cpp).
  std::vector<std::vector<std::uint32_t>> goalLists;
  std::vector<GroupCommand> commands;
  std::vector<core::Vec2> viewers;
  std::vector<std::uint32_t> rowOfId;       ///< stable id → row (kNoRow if gone), rebuilt when rows change
  bool rowsChanged = true;                  ///< set by spawning and by removals
  /// Rebuilds rowOfId when rows changed.
  void refreshRowOfId() {
    if (!rowsChanged) return;
    rowOfId.assign(spawner.nextAgentId(), kNoRow);
    for (std::size_t r = 0; r < agents.size(); ++r) rowOfId[agents.id[r]] = static_cast<std::uint32_t>(r);
    rowsChanged = false;
  }
  // Row order (row_order.cpp): rows in ascending id order until sortRows first sorts them spatially.
  bool rowsById = true;
  std::vector<std::uint32_t> idOrder;         ///< rowsInIdOrder's answer
  /// Whether this world keeps its rows in spatial order now (desc.rowOrder, the agents present).
  [[nodiscard]] bool keepsRowsSpatially() const;
  /// After emit: every kRowSortPeriod, rows sorted along the Hilbert curve of the grid's cells.
  void sortRows(const core::TaskSystem& tasks);
  /// The rows in ascending id order (for frames); empty while the rows are in id order themselves.
  [[nodiscard]] std::span<const std::uint32_t> rowsInIdOrder();
  /// The row of agent `id`, kNoRow if absent (rowOfId when it is current, else a search).
  [[nodiscard]] std::uint32_t rowOf(std::uint32_t id) const;
  bool anySociological = false;                   ///< some population has the sociological model on

  // Exit choice (exit_choice.hpp): distance fields, queues, the groups that choose.
  ExitChoice exitChoice;
  /// Per point, 1 while the timeline holds that exit closed: nobody leaves through it (decide);
  /// shorter than the points until a timeline entry closes one.
  std::vector<std::uint8_t> closedExits;
  /// The world's own copy of the navmesh when the scenario has exits (World::create): closing an
  /// exit closes the polygons of its region (nav::NavMesh::setClosed), so a closed door is a wall.
  std::shared_ptr<nav::NavMesh> ownMesh;
  /// Per exit point: the navmesh polygons of its region (found when it first closes).
  std::map<std::uint32_t, std::vector<nav::PolyRef>> doorPolys;
  /// Meshes this world planned on before a rebuild (cutExitsIntoMesh), kept so that references
  /// World::navMesh() handed out stay valid for the world's lifetime (one per rebuild).
  std::vector<std::shared_ptr<const nav::NavMesh>> retiredMeshes;
  /// Whether the world's mesh can be built again from its description (walkable polygons or
  /// terrain triangles; a host may hand World::create a mesh built from elsewhere).
  [[nodiscard]] bool meshRebuildable() const { return !desc.walkable.empty() || !desc.terrain.empty(); }
  /// Whether exit `point`'s region is one the mesh was cut for (NavMeshConfig::cuts).
  [[nodiscard]] bool exitCut(std::uint32_t point) const;
  /// Rebuilds the navmesh with every exit's region cut that is not yet (exits of crowds
  /// World::insertCrowd brought), and moves everything that plans on it to the new mesh: queries,
  /// path searches, walls, exit choice and transport fields, the doors closed so far, every
  /// agent's polygon. False (nothing changed) when every exit is cut, when the mesh cannot be
  /// rebuilt, or when the build fails.
  bool cutExitsIntoMesh();
  /// The mesh cut for every exit, built in the background from when a crowd brings exits the mesh
  /// is not cut for (startCutBuild) until one of them closes (cutExitsIntoMesh takes it, or builds
  /// anew when more exits came since): the same mesh, built without holding up the tick that
  /// closes the door when the close comes later than the build takes.
  struct CutBuild {
    std::vector<nav::CutRegion> cuts;
    std::future<core::Result<std::shared_ptr<const nav::NavMesh>>> mesh;
  };
  CutBuild cutBuild;
  /// The regions the mesh would be cut for with every exit's: its config's cuts, then the exits'
  /// not among them in point order; as many as it has when every exit is cut.
  [[nodiscard]] nav::NavMeshConfig configWithEveryExit() const;
  /// Starts building the mesh of configWithEveryExit() in the background (cutBuild) when it cuts
  /// more than the mesh does and the mesh can be rebuilt.
  void startCutBuild();
  /// The wall grid of the navmesh's boundary (creation and cutExitsIntoMesh).
  void buildWalls();
  /// The exit's floor closes or opens: path searches start again on the mesh as it is, agents
  /// whose way ran through it (closing) or who walk a path (opening) re-plan, and anyone standing
  /// in a closing door steps out to the nearest open floor (insert.cpp).
  void closeDoorFloor(std::uint32_t point, bool closed);
  /// Re-evaluates exits (after applyCommands, before sense).
  void chooseExits(const core::TaskSystem& tasks);

  // Per-point action clips, and regions cut into sub-regions with their occupancy (goals.hpp).
  std::vector<std::uint16_t> pointClip;
  PointRegions pointRegions;
  OpenChoices openChoices;  ///< waypoint choices groups have still to make (goals.hpp)

  // Common Ground (common_ground.cpp, common_ground_play.cpp; its state in common_ground_state.hpp,
  // its group-pass steps' contexts in group_pass.hpp).
  CommonGroundState commonGround;
  /// The Common Ground state of the scenario's points, interests and animation clips (creation).
  void initCommonGround();

  // Threads.
  mutable std::vector<WorkerScratch> scratch;
  std::vector<ChunkOutput> chunks;
  /// Events since the last frame taken (spawn events are kept compactly by the spawner until then).
  std::vector<Event> pendingEvents;

  // Inserted crowds (insert.cpp, crowd_insertion.hpp).
  CrowdInsertion insertion;
  /// Checks a crowd against the world and the crowds queued before it (nothing changes on failure).
  [[nodiscard]] core::Diagnostics checkCrowd(const CrowdDesc& crowd) const;
  std::uint32_t queueCrowd(const CrowdDesc& crowd);
  void initTimeline();
  /// Timeline entries and API crowd commands due this tick, in that order (from applyCommands).
  void applyCrowdCommands();
  void insertCrowdNow(CrowdState& crowd);
  /// The crowd's populations, with indices into the world's lists and times from `now` [s].
  void addCrowdPopulations(const CrowdDesc& crowd, std::uint32_t firstPoint, std::uint32_t firstPopulation, double now);
  /// Optional agent columns populations [firstPopulation, end) need and the world did not have yet.
  void addColumnsFor(std::uint32_t firstPopulation);
  void removeCrowdNow(CrowdState& crowd);
  /// Closes or opens exit `point` now (the timeline, World::setExitOpen): exit choice and decide.
  void setExitClosedNow(std::uint32_t point, bool closed);
  /// Agents queued by World::removeAgents, in call order; applied after the crowd commands.
  std::vector<std::uint32_t> agentRemovals;
  void removeAgentsNow();
  [[nodiscard]] bool crowdsPending() const {
    return !insertion.commands.empty() || !agentRemovals.empty() || insertion.timelineNext < desc.timeline.size();
  }

  // Phases.
  /// Groups of the scenario's populations, their sizes and the agent columns they need (creation).
  void planPopulations();
  /// The timeline's and the API's crowd commands due this tick (insert.cpp), exit choice's
  /// distance fields rebuilt when doors closed or opened (ExitChoice::refresh; tasks = nullptr:
  /// serially), then the populations due (spawnDue, spawner.hpp).
  void applyCommands(const core::TaskSystem* tasks = nullptr);
  void sense(const core::TaskSystem& tasks);
  /// decide (decide.cpp, phases.hpp), then the group pass.
  void decide(const core::TaskSystem& tasks);
  void decideGroups(const core::TaskSystem& tasks);  ///< group pass (groups.cpp), after the per-agent part of decide
  void plan(const core::TaskSystem& tasks);
  void steer(const core::TaskSystem& tasks);
  void integrate(const core::TaskSystem& tasks);
  /// After integrate, for the populations whose model corrects positions (OperationalModel::
  /// separationPasses): that many Jacobi passes, each row's step apart slid along the navmesh.
  void separate(const core::TaskSystem& tasks);
  /// Two floats a row whose use changes over the tick, so that no phase keeps its own: from the
  /// start of steer to its end, every row's preferred velocity of the previous tick
  /// (ModelInput::priorDesiredX/Y; swapped with AgentStore::prefVel, nothing copied); in separate,
  /// the displacements of the current pass [m]; in sortRows, the columns' scratch (spareX's bytes).
  /// Nothing of them outlives the phase.
  std::vector<float> spareX, spareY;
  std::vector<std::uint8_t> sepMoved;  ///< separate: 1 for a row the last pass moved
  VerticalTransports transports;          ///< lifts and escalators (vertical_transport.hpp): after separate
  TransportRoutes transportRoutes;        ///< choosing them (transport_choice.hpp): in setGoal
  int separationPasses = 0;       ///< the most passes any population asks for (configureModels)
  void emit();

  // Helpers shared by phases.
  void ensureScratch(const core::TaskSystem& tasks);
  /// What writing goals needs (goals.hpp): setGoal, drawTarget, releaseTarget, … (serial code).
  [[nodiscard]] GoalWriter goalWriter() {
    const bool routes = transportRoutes.active();
    return {desc,   groups, goalLists, pointRegions, openChoices, agents, *mainQuery, tick, pendingEvents,
            routes ? &transportRoutes : nullptr, routes ? &transports : nullptr};
  }
  /// What the phases may ask about goals (phases.hpp, goals.cpp); the two below (the API's) use it.
  [[nodiscard]] GoalView goalView() const { return {groups, goalLists, agents.group, agents.goalCursor}; }
  /// The point the group is heading for (its cursor in its active list), kNoPoint past the last.
  [[nodiscard]] std::uint32_t groupGoalPoint(const GroupState& g) const;
  /// The point `row` is heading for (from its group's active goal list), kNoPoint past the last.
  [[nodiscard]] std::uint32_t currentGoalPoint(std::size_t row) const;
  /// Formation (formGroups, phases.hpp): the group pass's parallel last step.
  void updateGroupShapes(const core::TaskSystem& tasks);
  void updateLeaders();  ///< updateLeaders(LeaderInput, LeaderOutput), phases.hpp
  [[nodiscard]] float dt() const { return desc.dt; }
  [[nodiscard]] static std::size_t grainFor(std::size_t n, const core::TaskSystem& tasks) { return phaseGrain(n, tasks); }

  // Partition (partition.hpp, partition.cpp): the steer phase shared with other ranks.
  PartitionState partition;
  /// Chooses (every partition.options.rebalanceTicks ticks) the cuts and this tick's owner of every row.
  void assignOwners();
  /// Sends what steer wrote for the owned rows, applies every other rank's values.
  void exchangeSteer();

  // The avoidance models (models/), steer's second part (steer(SteerInput, SteerOutput): steer.cpp).
  /// One instance per model some population walks with, by ModelKind (null: unused).
  std::array<std::unique_ptr<OperationalModel>, kModelCount> models;
  /// Creates the models the populations need and (re)reads their parameters (creation, insertion; world.cpp).
  void configureModels();
  /// Whether a model in use reads the previous tick's preferred velocities (ModelInput::priorDesiredX/Y).
  [[nodiscard]] bool modelsReadPrior() const;
  /// Gives a worker the scratch of every model in use (world.cpp).
  void addModelScratch(WorkerScratch& ws) const;
};

}  // namespace throng::sim

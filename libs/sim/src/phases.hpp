// The phases of the tick as functions whose signatures say what they read and what they may write
// (in the style of the operational-model seam, models/operational_model.hpp: ModelInput /
// VelocityOutput). Each phase takes a const …Input — what it reads — and a …Output — spans of the
// AgentStore columns and the owned parts it may write. World::Impl builds both from its state
// (world.cpp) and World::step calls the phases in order; the phase files see this header only, not
// World::Impl:
//   sense      SenseInput, SenseOutput          sense.cpp
//   decide     DecideInput, DecideOutput        decide.cpp (+ generateGoal, common_ground.cpp);
//              then the group pass (World::Impl::decideGroups, groups.cpp): its serial steps'
//              contexts are in group_pass.hpp, its last steps here: updateLeaders(LeaderInput,
//              LeaderOutput), formGroups(FormationInput, FormationOutput)
//   plan       PlanInput, PlanOutput            plan.cpp
//   steer      SteerInput, SteerOutput          steer.cpp (the models: ModelInput / VelocityOutput)
//   integrate  IntegrateInput, IntegrateOutput  integrate.cpp
//   emit       EmitInput, EmitOutput            emit.cpp; and the frame a caller takes between
//              ticks: takeFrame(FrameInput, FrameOutput), emit.cpp
// (The tick's first phase, spawning, is spawnDue(SpawnInput, SpawnOutput): spawner.hpp.)
// Also here: what the parallel phases share — the per-worker scratch, the per-chunk outputs and
// their grain — and the read-only view of where agents are going (GoalView, goals.cpp).
// Optional columns (AgentStore's column groups: levels, Common Ground, …) are passed as empty spans
// when the world does not have them.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "agent_store.hpp"
#include "common_ground_state.hpp"
#include "group_table.hpp"
#include "models/operational_model.hpp"
#include "throng/core/parallel.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"
#include "throng/sim/scenario.hpp"
#include "throng/sim/spatial_grid.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {

struct GoalWriter;  // goals.hpp
class Spawner;      // spawner.hpp

/// Per-worker scratch: navmesh queries and buffers reused across agents (never shared by threads).
struct WorkerScratch {
  std::unique_ptr<nav::NavQuery> query;
  /// Per ModelKind: the model's working memory, made by the model (models/operational_model.hpp).
  std::array<std::unique_ptr<ModelScratch>, kModelCount> modelScratch;
  std::vector<std::pair<float, std::uint32_t>> order, line;  // formation
};

/// Per-chunk outputs merged in chunk order (deterministic for any thread count).
struct ChunkOutput {
  std::vector<Event> events;
  double walkedDistance = 0.0;
  double walkingTime = 0.0;
  std::uint64_t socialMeetings = 0;
  float maxOverlap = 0.0f;           ///< deepest overlap of two bodies (discs) seen by decide [m]
  std::uint64_t overlapping = 0;     ///< agents overlapping a neighbour by more than kOverlapReported
  std::vector<std::uint32_t> pendingRows;  ///< rows whose goalPending was set, ascending
  std::vector<std::uint32_t> desireRows;   ///< rows whose desirePoint was set (goal generator), ascending
};

/// Overlaps of bodies deeper than this are counted in WorldStats::overlapAgentSteps [m].
inline constexpr float kOverlapReported = 0.01f;

/// The chunk size of the parallel phases over n agents: chunk c of a phase is rows
/// [c·grain, (c+1)·grain), and writes ChunkOutput c.
[[nodiscard]] inline std::size_t phaseGrain(std::size_t n, const core::TaskSystem& tasks) {
  return tasks.grain(n < 4096 ? 256 : 1024);
}

/// Where agents are going, read-only (goals.cpp): what the phases ask about goals.
struct GoalView {
  const GroupTable& groups;
  /// One goal list per population, then one per automatic-goals group (point indices).
  std::span<const std::vector<std::uint32_t>> goalLists;
  std::span<const std::uint32_t> group, goalCursor;  ///< AgentStore columns

  /// The goal list a group follows now: its own, or the followed group's while following.
  [[nodiscard]] const std::vector<std::uint32_t>& activeGoals(const GroupState& g) const;
  /// That list's index into goalLists.
  [[nodiscard]] std::uint32_t activeList(const GroupState& g) const;
  /// The point the group is heading for (its cursor in its active list), kNoPoint past the last.
  [[nodiscard]] std::uint32_t groupGoalPoint(const GroupState& g) const;
  /// The point `row` is heading for (from its group's active goal list), kNoPoint past the last.
  [[nodiscard]] std::uint32_t currentGoalPoint(std::size_t row) const;
  /// Starts fetching `row`'s group record into the cache (rows sorted spatially read their groups
  /// in no particular order: row_order.cpp). Phases call it kGroupPrefetch rows ahead.
  void prefetch(std::size_t row) const { __builtin_prefetch(&groups[group[row]]); }
};

/// How many rows ahead decide and steer fetch a row's group record (GoalView::prefetch).
inline constexpr std::size_t kGroupPrefetch = 8;

/// Whether `row` (of population `pop`) stops at the end of its current path — an action point's
/// stop, or its last goal when it does not wander —, so it slows down on the last leg (goals.cpp).
[[nodiscard]] bool stopsAtGoal(const GoalView& goals, std::span<const PointDesc> points, const PopulationDesc& pop,
                               std::size_t row);

/// Whether (x, y) lies inside a point's region (its disc, or its polygon).
[[nodiscard]] bool insideRegion(const PointDesc& point, float x, float y);

// ---- sense (sense.cpp): the spatial grid and every agent's k nearest neighbours.

struct SenseInput {
  std::span<const float> posX, posY;
  std::span<const float> posZ;   ///< floor heights; empty on a flat world (one level)
  const SteeringDesc& steering;  ///< maxNeighbours, neighbourDistance, denseNeighbourDistance, denseThreshold
  /// With lifts or escalators (else empty): people carried (GoalState::Riding and AgentMode::Acting,
  /// vertical_transport.cpp) are nobody's neighbours and have none: in a car or on a belt, not on the floor.
  std::span<const GoalState> goalState;
  std::span<const AgentMode> mode;
};

struct SenseOutput {
  SpatialGrid& grid;                           ///< rebuilt from the positions
  std::vector<std::uint32_t>& neighbours;      ///< resized to n·maxNeighbours: rows, nearest first
  std::vector<std::uint16_t>& neighbourCount;  ///< resized to n
};

/// Rebuilds the grid, then each agent's neighbours (parallel; each writes only its own slots).
void sense(const SenseInput& in, const SenseOutput& out, const core::TaskSystem& tasks);

// ---- decide (decide.cpp): the goal state machine of every agent (parallel; each row writes only
// its own entries of DecideOutput's columns and its chunk). The group pass then applies what it
// flagged (World::Impl::decideGroups, groups.cpp).

struct DecideInput {
  /// Every column, read-only: the row's own (position, id, group, ticket, …) and its neighbours'.
  /// The columns decide writes are read and written through DecideOutput instead.
  const AgentStore& agents;
  const ScenarioDesc& desc;   ///< dt, seed, points, populations, steering.maxNeighbours, social
  std::uint64_t tick;
  const GroupTable& groups;   ///< each agent's group: guided, flocking, members, cursor, coordination
  GoalView goals;             ///< the goal point each agent walks to
  const CommonGroundState& commonGround;  ///< categories and places (the goal generator)
  std::span<const WorkerScratch> workers; ///< per-worker navmesh queries (the goal generator's sight)
  /// Per point, 1 for an exit the timeline has closed: an agent reaching it waits there instead
  /// of leaving; may be shorter than the points (those beyond are open).
  std::span<const std::uint8_t> closedExits;
};

struct DecideOutput {
  std::span<GoalState> goalState;
  std::span<AgentMode> mode;
  std::span<float> targetX, targetY;
  std::span<float> targetZ;                   ///< empty on a flat world
  std::span<CornerPath> corners;              ///< cleared when the agent stops to wait
  std::span<std::uint8_t> needPath;           ///< → plan
  std::span<GoalPending> goalPending;         ///< → the group pass (rows listed in the chunk)
  std::span<float> progressDistance;          ///< the progress check's last distance [m]
  std::span<std::uint32_t> actionEndTick;
  std::span<float> oriX, oriY;                ///< turned to an action point's orientation
  std::span<SocialEffect> sociologicalEffect; ///< → the group pass; empty without the sociological model
  std::span<std::uint32_t> sociologicalOther; ///< the agent met; empty without the sociological model
  std::span<std::uint32_t> desirePoint;       ///< → the group pass; empty without Common Ground
  std::span<std::uint8_t> desireTrigger;      ///< its GoalTrigger; empty without Common Ground
  std::span<ChunkOutput> chunks;              ///< events, meetings, flagged rows; chunkCount(n, phaseGrain) of them
  std::span<float> dose;                      ///< carbon monoxide dose taken up (FED); empty without toxic smoke
};

/// Period of the progress check that triggers a re-plan for an agent that is stuck [s].
inline constexpr float kProgressCheckPeriod = 4.0f;
/// Seconds between an off-course walker's looks for the corner it walks to (decide.cpp, checkSight).
inline constexpr float kSightCheckPeriod = 0.25f;

/// Whether a step `vel` heads for the corner `toAim` away, within about 30° (cos² 0.75): a walker
/// off course may have been pushed out of sight of it (steer.cpp advanceCorner, decide.cpp checkSight).
[[nodiscard]] inline bool onCourse(core::Vec2 vel, core::Vec2 toAim) {
  constexpr float kOnCourseCos2 = 0.75f;
  const float toward = core::dot(vel, toAim);
  return toward > 0.0f && toward * toward >= kOnCourseCos2 * core::lengthSq(vel) * core::lengthSq(toAim);
}

/// The per-agent part of decide: arrivals, actions, exits, progress checks, the Common Ground goal
/// generator, sociological meetings.
void decide(const DecideInput& in, const DecideOutput& out, const core::TaskSystem& tasks);
/// The Common Ground goal generator for one agent (common_ground.cpp; decide calls it): may set
/// the row's desirePoint and desireTrigger and list the row in the chunk.
void generateGoal(const DecideInput& in, const DecideOutput& out, std::size_t row, ChunkOutput& chunk,
                  const nav::NavQuery& query);

// ---- the group pass's formation step (groups.cpp): members of flocking groups walk abreast
// (parallel over the busy groups; a group writes its own cold part and its members' rows only).

struct FormationInput {
  std::span<const PopulationDesc> populations;  ///< flocking, groupSpacing
  std::span<const std::uint32_t> rowOfId;       ///< stable id → row
  std::span<const float> posX, posY, velX, velY;
  std::span<const GoalState> goalState;
  std::span<const std::uint32_t> goalCursor;
  std::span<const std::uint32_t> followAgent;   ///< empty without the sociological model
};

struct FormationOutput {
  GroupTable& groups;                   ///< the busy groups' centroid and heading (GroupExtra)
  std::span<float> formVelX, formVelY;  ///< members' formation corrections [m/s]; empty when nobody flocks
  std::span<WorkerScratch> workers;     ///< per-worker sort buffers (order, line)
};

/// Each busy group's centroid and heading, and its walking members' corrections toward their slots.
void formGroups(const FormationInput& in, const FormationOutput& out, const core::TaskSystem& tasks);

// ---- the group pass's leader step (groups.cpp): every busy group has a leader among its members;
// with the sociological model, leadership may pass to the most dominant member (serial, group order).

struct LeaderInput {
  std::span<const PopulationDesc> populations;  ///< sociological: leaderChangeRate, domination
  std::uint64_t seed;
  float dt;                                     ///< [s]
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;       ///< stable id → row
  std::span<const std::uint16_t> population;    ///< AgentStore column (a member's dominance)
};

struct LeaderOutput {
  GroupTable& groups;           ///< the busy groups' leader
  std::vector<Event>& events;   ///< LeaderChange
};

void updateLeaders(const LeaderInput& in, const LeaderOutput& out);

// ---- plan (plan.cpp): budgeted path planning through nav::PathQueue (requests in row order; the
// searches on the workers, results independent of their number).

struct PlanInput {
  std::uint64_t tick;
  std::span<const std::uint32_t> id;                  ///< stable ids (events)
  std::span<const std::uint16_t> population;          ///< the route cost class (stairs) of a layered request
  std::span<const float> posX, posY, targetX, targetY;
  std::span<const float> posZ, targetZ;               ///< floor heights; empty on a flat world
  GoalView goals;                                     ///< the goal a PathPartial event names
  /// Workers the queue searches on ahead of the requests' turn (nav::PathQueue::update); results
  /// are the same with or without them. nullptr: on the calling thread.
  const core::TaskSystem* tasks = nullptr;
};

struct PlanOutput {
  std::span<std::uint8_t> needPath;     ///< cleared once the request is queued
  std::span<nav::PathTicket> ticket;    ///< the request pending, 0 once its path is handed over
  std::span<CornerPath> corners;        ///< the corners of a path that arrived
  nav::PathQueue& pathQueue;            ///< requests in, kPathIterationsPerTick node expansions spent
  std::vector<Event>& events;           ///< PathPartial
  std::span<std::vector<float>> cornerZ = {};  ///< the corners' floor heights; empty on a flat world
};

/// Detour node expansions the plan phase may spend per tick (time-slicing, as dtPathQueue).
inline constexpr int kPathIterationsPerTick = 20000;

/// Queues the rows that need a path, spends the tick's budget, hands finished paths to their rows.
void plan(const PlanInput& in, const PlanOutput& out);

// ---- steer (steer.cpp): every agent's preferred velocity, then its population's avoidance model
// (parallel; each row writes only its own entries). With a partition (partition.hpp) only the rows
// this rank owns.

struct SteerInput {
  const SteeringDesc& steering;  ///< cornerReach, levelLookAhead, arrivalTime, formationSpeedUp, stuckPatience, stuckAttempt
  std::uint64_t seed;            ///< deadlock breaking's draws
  std::span<const PopulationDesc> populations;  ///< wander (stopping at the last goal), model.kind, stairUp/Down
  std::span<const PointDesc> points;            ///< an action point's stop
  std::span<const std::uint32_t> id;
  std::span<const std::uint16_t> population;
  std::span<const float> posX, posY;
  std::span<const float> posZ;                  ///< floor heights; empty on a flat world
  std::span<const std::uint32_t> polyRef;       ///< navmesh polygon under the agent (stairs; multi-level worlds)
  std::span<const float> speed;                 ///< desired walking speed [m/s]
  std::span<const float> targetX, targetY;
  std::span<const GoalState> goalState;
  std::span<const std::uint8_t> scriptWalk;     ///< Common Ground scripts; empty without them
  std::span<const std::uint8_t> dynamicTarget;  ///< approached slowing down
  std::span<const float> formVelX, formVelY;    ///< the group pass's formation corrections; empty when nobody flocks
  std::span<const float> stuckTime;             ///< [s] (deadlock breaking)
  GoalView goals;                               ///< the goal point (does the path end in a stop?)
  RowRange rows;                                ///< the rows to steer: every row, or the partition's owned rows
  /// Per ModelKind: the model (null: no population walks with it).
  std::span<const OperationalModel* const> models;
  /// What the models read: every column — prefVel included, written by the first part of steer —,
  /// the walls, the scenario, the viewers.
  const ModelInput& model;
};

struct SteerOutput {
  std::span<float> prefVelX, prefVelY;  ///< the preferred velocity [m/s]
  std::span<CornerPath> corners;        ///< the corner walked to (CornerPath::index) moves on
  VelocityOutput newVel;                ///< the models' velocities [m/s], committed by integrate
  std::span<WorkerScratch> workers;     ///< per-worker navmesh queries (sight lines) and model scratch
};

/// Every row's preferred velocity (path corners, arrival, formation, deadlock breaking), then, for
/// runs of consecutive rows walking with the same model, that model's computeVelocities.
void steer(const SteerInput& in, const SteerOutput& out, const core::TaskSystem& tasks);

// ---- integrate (integrate.cpp): commits the models' velocities (parallel; each row writes its own).

struct IntegrateInput {
  float dt;                                   ///< [s]
  std::uint64_t tick;
  std::span<const float> newVelX, newVelY;    ///< the models' velocities from steer [m/s]
  std::span<const std::uint8_t> holdHeading;  ///< 1: the model keeps the body from turning this tick
  std::span<const float> prefVelX, prefVelY;  ///< the preferred (desired) velocities from steer [m/s]
  std::span<const GoalState> goalState;
  std::span<const AgentMode> mode;
  std::span<const float> speed;               ///< desired walking speed [m/s] (stuck detection)
  std::span<const std::uint32_t> actionEndTick;
  std::span<const std::uint8_t> scriptWalk;   ///< Common Ground scripts; empty without them
  std::span<const std::uint16_t> scriptClip;  ///< Common Ground scripts; empty without them
  GoalView goals;                             ///< the point an acting agent acts at
  std::span<const PointDesc> points;          ///< actionDuration of that point
  std::span<const std::uint16_t> pointClip;   ///< per point: its action's animation clip
  std::span<const float> clipDuration;        ///< per animation clip [s] (script clips)
  std::span<const WorkerScratch> workers;     ///< per-worker navmesh queries (moveAlongSurface)
};

struct IntegrateOutput {
  std::span<float> posX, posY;        ///< moved along the navmesh surface
  std::span<float> posZ;              ///< floor height under the agent; empty on a flat world
  std::span<std::uint32_t> polyRef;   ///< navmesh polygon under the agent
  std::span<float> velX, velY;        ///< the displacement actually made, over dt [m/s]
  std::span<float> stuckTime;         ///< [s] (deadlock breaking in steer)
  std::span<std::uint16_t> animClip;
  std::span<float> animPhase;
  std::span<float> oriX, oriY;        ///< heading, turned toward the motion
  std::span<ChunkOutput> chunks;      ///< walking distance and time; TaskSystem::chunkCount(n, phaseGrain) of them
};

/// Moves every agent by its new velocity along the navmesh, then its statistics, animation, heading.
void integrate(const IntegrateInput& in, const IntegrateOutput& out, const core::TaskSystem& tasks);

// ---- emit (emit.cpp): the tick's outputs merged, the agents that left removed, the clock moved
// on (serial).

struct EmitInput {
  std::uint64_t tick;  ///< the tick ending
  float dt;            ///< [s]
};

struct EmitOutput {
  std::span<ChunkOutput> chunks;  ///< decide's and integrate's events and sums, merged in chunk order, then emptied
  std::vector<Event>& events;     ///< the world's pending events: the chunks' events appended
  /// exited, lastExitTime, walkedDistance, walkingTime, socialMeetings, agentSteps; tick, time and
  /// active as of the next tick
  WorldStats& stats;
  AgentStore& agents;             ///< rows of agents that exited (GoalState::Exited) removed, the rest in order
  GroupTable& groups;             ///< agents that exited leave their groups
  GoalWriter& goals;              ///< agents that exited release their targets' sub-regions
};

/// Merges the chunks into the events and statistics, then removes the agents that exited (stable
/// compaction: rows stay in id order). Returns whether rows were removed (stable id → row changes).
bool emit(const EmitInput& in, const EmitOutput& out);

/// Agent `row` leaves the world (it exited, or its crowd was removed): it releases its target's
/// sub-region and leaves its group (the leader passes to the first member left). Its row stays
/// until the store is compacted.
void leaveWorld(std::size_t row, GoalWriter& goals, GroupTable& groups);

// ---- the frame (emit.cpp): a snapshot of every agent and what happened since the last one.

struct FrameInput {
  const AgentStore& agents;  ///< ids, positions (floor heights on multi-level worlds), velocities, headings, modes, animation
  std::uint64_t tick;
  float dt;                  ///< [s]
  /// The rows in ascending id order when the rows are not in that order themselves (spatial row
  /// order, row_order.cpp); empty: row order is id order.
  std::span<const std::uint32_t> idOrder;
};

struct FrameOutput {
  Spawner& spawner;                  ///< the spawn events it kept compactly, written out and emptied
  std::vector<Event>& events;        ///< the world's pending events, taken (emptied)
  CommonGroundState& commonGround;   ///< pendingScript, pendingCoordinations taken (emptied)
};

/// The frame of tick `in.tick`: the agents' columns, and the events, script entries and
/// coordinations since the last frame taken (which this hands over).
[[nodiscard]] FramePtr takeFrame(const FrameInput& in, const FrameOutput& out);

}  // namespace throng::sim

// The group pass's serial steps (groups.cpp) as functions of their contexts, in the style of the
// phases (phases.hpp): a const …Input — what the step reads — and a …Output — the GroupTable, the
// agent columns (spans) it writes itself, the GoalWriter (goals.hpp) through which it changes
// goals, and its events. World::Impl::decideGroups builds them and calls the steps in order:
//   applyGroupCommands  GroupCommand span, GroupTable      API guide / release
//   updateGuidance      GuidanceInput, GuidanceOutput      dynamic goals behind a guide (§3.2.6)
//   updateFollowing     FollowingInput, FollowingOutput    following another group (§3.2.5)
//   applySocialEffects  SocialEffectsInput, SocialEffectsOutput  sociological meetings (§3.2.1 iii)
//   updateWaiting       WaitingInput, WaitingOutput        the wait rule (flocking rule 4, §3.2.3)
//   startCoordinations, runCoordinations, checkReunions   CommonGroundInput, CommonGroundOutput
//                       the Common Ground model (common_ground.cpp, common_ground_play.cpp)
// (updateLeaders and formGroups, the last steps, are in phases.hpp.) Groups are visited in
// stable-id order (the busy set), agents in row order and coordinations in start order.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "agent_store.hpp"
#include "common_ground_state.hpp"
#include "goals.hpp"
#include "group_table.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// A command from the World API, applied in order at the start of the next tick's group pass.
struct GroupCommand {
  std::uint32_t group = 0;
  bool guide = false;  ///< false = release
  core::Vec2 position;
  float height = 0.0f;  ///< the guide's floor height [m] (multi-level worlds)
};

/// Guide / release commands: the groups' routes (guidedByApi, guide, guideHeight).
void applyGroupCommands(std::span<const GroupCommand> commands, GroupTable& groups);

// ---- guidance: a guided group's members walk to slots behind the guide (API or script).

struct GuidanceInput {
  std::span<const PopulationDesc> populations;  ///< guide (script, distance, release), groupSpacing
  float dt;                                     ///< [s]
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;       ///< stable id → row
};

struct GuidanceOutput {
  GroupTable& groups;  ///< guided; routes (guide, guidePlanned); reads extras (centroid, heading)
  /// Members' dynamic targets (read: goalState, to skip exited agents and those holding their own).
  std::span<GoalState> goalState;
  std::span<AgentMode> mode;
  std::span<float> targetX, targetY;
  std::span<float> targetZ;                 ///< empty on a flat world
  std::span<std::uint8_t> dynamicTarget, needPath;
  std::span<CornerPath> corners;
  GoalWriter& goals;          ///< members back to the group's goals when guidance ends; its query snaps targets
  std::vector<Event>& events; ///< GuideStart, GuideEnd
};

void updateGuidance(const GuidanceInput& in, const GuidanceOutput& out);

// ---- following: a group with a followed group adopts that group's goal list while it follows.

struct FollowingInput {
  std::span<const PopulationDesc> populations;  ///< follow (mode, on/off period bounds)
  std::uint64_t seed;
  float dt;                                     ///< [s]
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;       ///< stable id → row
  /// Read before each member's goal is set (GoalWriter rewrites it for the rows it sets).
  std::span<const GoalState> goalState;
};

struct FollowingOutput {
  GroupTable& groups;          ///< following, cursor; routes (ownCursor, followToggle); extras (waiting)
  GoalWriter& goals;           ///< members to the adopted (or own) list's goal
  std::vector<Event>& events;  ///< FollowStart, FollowEnd
};

void updateFollowing(const FollowingInput& in, const FollowingOutput& out);

// ---- sociological effects: following another agent, joining its group (every row, row order).

struct SocialEffectsInput {
  const ScenarioDesc& desc;                ///< seed, dt; populations (sociological, flocking, speeds)
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;  ///< stable id → row
  std::span<const std::uint32_t> id;
  std::span<const std::uint16_t> population;
  std::span<const float> posX, posY;
  std::span<const float> posZ;             ///< empty on a flat world
  std::span<const std::uint32_t> sociologicalOther;  ///< the agent met (decide)
  std::span<const std::uint32_t> goalCursor;  ///< back to its own goal (GoalWriter rewrites it)
};

struct SocialEffectsOutput {
  GroupTable& groups;                         ///< members, leader, busy set of the groups joined and left
  std::span<std::uint32_t> followAgent, followUntil;
  std::span<SocialEffect> sociologicalEffect; ///< read and cleared
  std::span<std::uint32_t> group;
  std::span<std::uint16_t> groupSize;
  std::span<float> speed;                     ///< a joiner walks at its new group's speed
  std::span<float> targetX, targetY;
  std::span<float> targetZ;                   ///< empty on a flat world
  std::span<std::uint8_t> dynamicTarget, needPath;
  std::span<GoalState> goalState;             ///< read too (exited, acting)
  std::span<AgentMode> mode;
  GoalWriter& goals;                          ///< back to its goal, or the joined group's
  std::vector<Event>& events;                 ///< FollowAgent, FollowAgentEnd, JoinGroup
};

void applySocialEffects(const SocialEffectsInput& in, const SocialEffectsOutput& out);

// ---- waiting: a flocking group waits at each goal for its members (or a timeout), then moves on.

struct WaitingInput {
  std::span<const PopulationDesc> populations;  ///< flocking, waitTimeout
  float dt;                                     ///< [s]
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;       ///< stable id → row
  std::span<const std::uint32_t> goalCursor;    ///< a non-flocking group's cursor is its leader's
  /// Read before each member's goal is set (GoalWriter rewrites it for the rows it sets).
  std::span<const GoalState> goalState;
};

struct WaitingOutput {
  GroupTable& groups;          ///< cursor; extras (waiting, waitStart)
  GoalWriter& goals;           ///< released members to the next goal; the goal point of the events
  std::vector<Event>& events;  ///< GroupWaitStart, GroupRelease, GroupTimeout
};

void updateWaiting(const WaitingInput& in, const WaitingOutput& out);

// ---- Common Ground (Park et al.; docs/social-model.md): desires become coordinations — action
// scripts for a group's members, or lone visits — which are played entry by entry; divided
// groups reunite. Runs only when the scenario's social model is on.

struct CommonGroundInput {
  const ScenarioDesc& desc;                ///< social, points, populations (preferences, groupSpacing), seed, dt
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;  ///< stable id → row
};

struct CommonGroundOutput {
  /// Reads the actors' and mates' position, heading, radius, speed, id, group, population,
  /// interests, goal state and desire; writes the actors' rows: desirePoint, coordination,
  /// goalState, mode, scriptWalk, scriptClip, target, corners, needPath, ticket, dynamicTarget,
  /// progressDistance, stuckTime, heading (turns), socialReady, visited.
  AgentStore& agents;
  GroupTable& groups;             ///< the group's coordination and reunite; busy set
  CommonGroundState& state;       ///< coordinations, their ids, clips; finished script entries and records
  GoalWriter& goals;              ///< the goal's spot (drawTarget), back to the group's goal (setGoal); its query
  std::vector<Event>& events;     ///< GoalGenerated, Coordination*, Visit*, Reunited
};

/// What both Common Ground passes work on, bound from their contexts (common_ground.cpp,
/// common_ground_play.cpp each derive their steps from it).
struct CommonGroundPass {
  const ScenarioDesc& desc;
  std::uint64_t tick;
  std::span<const std::uint32_t> rowOfId;
  AgentStore& agents;
  GroupTable& groups;
  CommonGroundState& commonGround;
  GoalWriter& goals;
  std::vector<Event>& pendingEvents;

  CommonGroundPass(const CommonGroundInput& in, const CommonGroundOutput& out)
      : desc(in.desc), tick(in.tick), rowOfId(in.rowOfId), agents(out.agents), groups(out.groups),
        commonGround(out.state), goals(out.goals), pendingEvents(out.events) {}
};

/// Desires flagged by decide (the chunks' desireRows, cleared) become coordinations: the grounding
/// planner's script for the initiator and its mates, or a lone visit (common_ground.cpp).
void startCoordinations(const CommonGroundInput& in, const CommonGroundOutput& out, std::span<ChunkOutput> chunks);
/// Plays every active script one tick; finished ones are published (common_ground_play.cpp).
void runCoordinations(const CommonGroundInput& in, const CommonGroundOutput& out);
/// Groups divided by a coordination that are whole again (Reunited) (common_ground_play.cpp).
void checkReunions(const CommonGroundInput& in, const CommonGroundOutput& out);

/// Flocking rule 2: one walking speed per group, drawn from its population's distribution (the
/// group's own stream: the same value whenever it is drawn) [m/s] (spawn.cpp).
[[nodiscard]] float groupSpeed(const ScenarioDesc& desc, const GroupTable& groups, std::uint32_t gid);

}  // namespace throng::sim

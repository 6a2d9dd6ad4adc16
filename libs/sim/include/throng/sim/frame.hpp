// throng::sim::Frame — an immutable snapshot the `emit` phase publishes. Consumers (the recorder
// on its own thread, the server, the CLI's progress bar) read frames and never touch the World.
// Agents are named by stable spawn-order ids (0, 1, 2 … in spawn order), never by row or slot.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace throng::sim {

/// What an agent is doing, as the animation layer would play it.
enum class AgentMode : std::uint8_t {
  Walking = 0,
  Waiting = 1,  ///< standing (no path yet, or nothing to do)
  Acting = 2,   ///< stopped at an action point, playing its action
};

enum class EventKind : std::uint8_t {
  Spawn = 0,        ///< a = population index, b = group id
  Exit = 1,         ///< a = exit point index, or 0xffffffff when removed: b = its crowd's index, or 0xffffffff (World::removeAgents)
  GoalReached = 2,  ///< a = point index
  ActionStart = 3,  ///< a = point index
  ActionEnd = 4,    ///< a = point index
  PathPartial = 5,  ///< a = point index the agent could not fully reach; it walks to the closest point
  GroupWaitStart = 6,  ///< first member of a group arrived and waits; a = point, b = group
  GroupRelease = 7,    ///< every member arrived, the group goes on; a = point, b = group
  GroupTimeout = 8,    ///< the wait timed out, present members go on; a = point, b = members missing
  FollowStart = 9,     ///< agent = leader of the following group; a = following group, b = followed group
  FollowEnd = 10,      ///< a = following group, b = followed group
  GuideStart = 11,     ///< agent = the group's leader; a = group
  GuideEnd = 12,       ///< a = group
  JoinGroup = 13,      ///< sociological: agent changed group; a = old group, b = new group
  FollowAgent = 14,    ///< sociological: agent follows another agent for a while; a = that agent's id
  FollowAgentEnd = 15, ///< a = the agent it followed
  LeaderChange = 16,   ///< agent = new leader; a = group
  PathFallback = 17,   ///< no valid Bézier curve: the navmesh path is used; a = point index
  // Common Ground (Park et al.; docs/social-model.md).
  GoalGenerated = 18,     ///< the goal generator gave the agent a goal; a = point, b = GoalTrigger
  CoordinationStart = 19, ///< agent = initiator A; a = coordination id, b = group
  CoordinationEnd = 20,   ///< agent = initiator A; a = coordination id, b = CoordinationOutcome
  VisitStart = 21,        ///< the agent reached a generated goal and stays; a = point, b = coordination id
  VisitEnd = 22,          ///< a = point, b = coordination id
  Reunited = 23,          ///< the group is whole again after a divide; agent = A, a = group, b = coordination id
  // Exit choice (docs/crowd-model.md "Tactical level: exit choice").
  ExitChosen = 24,  ///< agent = the group's leader; a = the exit it heads for now, b = the one before (kNoPoint: first choice)
  // Waypoint choices (PopulationDesc::goalChoices; docs/scenario-format.md "Waypoint choices").
  WaypointChosen = 25,  ///< agent = the group's leader; a = the point chosen, b = the choice's slot (index into the
                        ///< population's goals); once per group, when its first member reaches the slot
  // Toxicity (smoke's carbon monoxide; docs/scenario-format.md "Smoke").
  Incapacitated = 26,   ///< the agent's dose reached its population's incapacitationDose: it stops for good;
                        ///< a = the dose in thousandths (FED × 1000, rounded)
};

/// Why the goal generator gave an agent a goal.
enum class GoalTrigger : std::uint8_t {
  Need = 0,        ///< stochastic, at a rate per agent (a restroom visit)
  Attraction = 1,  ///< the agent saw a point of a category it is interested in (a store)
};

/// How a Common Ground interaction ended.
enum class CoordinationOutcome : std::uint8_t {
  Grounded = 0,  ///< common ground reached: the agreed macro-plan was carried out
  Failed = 1,    ///< a grounding step ran out of attempts: the fallback (resume) was carried out
  Alone = 2,     ///< no coordination: the agent has no group mate present, or Common Ground is off
};

struct Event {
  std::uint64_t tick = 0;
  std::uint32_t agent = 0;  ///< stable id
  EventKind kind = EventKind::Spawn;
  std::uint32_t a = 0;
  std::uint32_t b = 0;
};

/// One entry of a character's action script (Common Ground; Park et al. Tables 3 and 5) as the
/// simulation carried it out, published when the entry ends. Enum fields hold the values of
/// throng::common_ground's enums (the frame stays free of that library's headers).
struct ScriptRecord {
  std::uint32_t coordination = 0;  ///< CoordinationRecord::id
  std::uint32_t agent = 0;         ///< stable id of the character
  std::uint32_t seq = 0;           ///< position in this character's script for this coordination (0, 1, ...)
  std::uint8_t role = 0;           ///< 0 initiator A, 1 respondent B, 2 companion (another group mate)
  std::uint8_t step = 7;           ///< common_ground::GroundingStep, 1..7 (Table 1)
  std::uint8_t part = 0;           ///< proposal part of steps 4 and 5: 1 = "a", 2 = "b"; 0 otherwise
  std::uint8_t attempt = 0;        ///< 0 first try, then retries
  std::uint8_t plan = 0;           ///< common_ground::PlanKind proposed or executed
  std::uint8_t targetType = 0;     ///< 0 none, 1 point, 2 agent
  std::uint32_t targetAgent = 0xffffffffu;  ///< stable id when targetType == 2
  float targetX = 0.0f, targetY = 0.0f;     ///< target point [m] (the agent's position for agents)
  double plannedStart = 0.0;       ///< start time the planner predicted [s]
  double plannedDuration = 0.0;    ///< duration the planner predicted [s]
  double start = 0.0;              ///< when the simulation started it [s]
  double duration = 0.0;           ///< how long it lasted in the simulation [s]
  std::string motion;              ///< clip name, or "walk" / "turn" / "idle"
  std::string behaviour;           ///< micro-behaviour ("wave") or macro step ("walk_to_goal", "stay", "wait")
};

/// One Common Ground interaction (or a lone visit), published when it ends.
struct CoordinationRecord {
  std::uint32_t id = 0;            ///< unique, in order of start
  std::uint32_t group = 0;         ///< stable group id
  std::uint32_t initiator = 0;     ///< stable id of A
  std::vector<std::uint32_t> respondents;  ///< stable ids: B first, then the companions; empty when Alone
  std::uint32_t goalPoint = 0;     ///< index into ScenarioDesc::points
  std::uint8_t goalKind = 0;       ///< common_ground::GoalKind (0 personal, 1 shared)
  GoalTrigger trigger = GoalTrigger::Need;
  std::uint8_t relation = 0;       ///< common_ground::Relation of A to B at initiation (1..6); 0 when Alone
  std::uint8_t plan = 0;           ///< common_ground::PlanKind carried out
  CoordinationOutcome outcome = CoordinationOutcome::Alone;
  std::uint32_t retries = 0;       ///< grounding attempts beyond the first, over all steps
  double start = 0.0;              ///< t_0 [s]
  double executeTime = 0.0;        ///< when the macro-plan (or fallback) started [s]
  double end = 0.0;                ///< when the last actor left the script [s]
};

struct Frame {
  std::uint64_t tick = 0;
  double time = 0.0;  ///< tick * dt [s]
  std::vector<std::uint32_t> ids;  ///< stable ids of the agents present, ascending
  std::vector<float> posX, posY;   ///< [m]
  std::vector<float> posZ;         ///< height [m] on a multi-level world; empty on a flat one (all 0)
  std::vector<float> velX, velY;   ///< [m/s]
  std::vector<float> oriX, oriY;   ///< unit heading
  std::vector<AgentMode> mode;
  std::vector<std::uint16_t> clip; ///< motion clip playing: index into animationClips(scenario)
  std::vector<float> phase;        ///< position in that clip, [0, 1)
  std::vector<Event> events;       ///< everything that happened since the previous frame, in order
  std::vector<ScriptRecord> script;              ///< action-script entries ended since the previous frame
  std::vector<CoordinationRecord> coordinations; ///< interactions ended since the previous frame

  [[nodiscard]] std::size_t size() const { return ids.size(); }
  /// Height of the i-th agent [m] (0 on a flat world).
  [[nodiscard]] float height(std::size_t i) const { return posZ.empty() ? 0.0f : posZ[i]; }
};

using FramePtr = std::shared_ptr<const Frame>;

}  // namespace throng::sim

// throng::sim::World — owns the agents and runs the tick as explicit phases:
//   applyCommands → sense → decide → plan → steer → integrate → emit
// Each phase is a function over the structure-of-arrays AgentStore, parallel over agents with a
// compute/commit split, so one seed gives identical trajectories for any thread count. The World
// does no I/O: no files, sockets, logging or clocks; time is an integer tick times a fixed dt.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/handle.hpp"
#include "throng/core/parallel.hpp"
#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/frame.hpp"
#include "throng/sim/partition.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// Running totals; reductions are per fixed chunk, combined in chunk order (deterministic).
struct WorldStats {
  std::uint64_t tick = 0;
  double time = 0.0;                 ///< [s]
  std::uint32_t spawned = 0;
  std::uint32_t exited = 0;
  std::uint32_t removed = 0;         ///< agents removed with their crowd or by id (World::removeAgents; not in `exited`)
  std::uint32_t active = 0;          ///< in the world now
  std::uint32_t scheduled = 0;       ///< still to spawn
  double lastExitTime = -1.0;        ///< [s]; < 0 when nobody exited
  double walkedDistance = 0.0;       ///< summed over agents [m]
  double walkingTime = 0.0;          ///< agent-seconds spent walking (mode Walking) [s]
  std::uint64_t agentSteps = 0;      ///< sum over ticks of active agents
  std::uint64_t socialMeetings = 0;  ///< sociological model: meeting rolls made (agent, other-group agent, tick)
  /// Bodies overlapping (two discs closer than the sum of their radii), measured each tick before
  /// anyone moves: the deepest overlap so far [m], and the agent-steps overlapping a neighbour by
  /// more than 1 cm (agentSteps counts them all).
  double maxOverlap = 0.0;
  std::uint64_t overlapAgentSteps = 0;

  /// Mean walking speed over all agents and time spent walking [m/s].
  [[nodiscard]] double meanWalkingSpeed() const { return walkingTime > 0 ? walkedDistance / walkingTime : 0.0; }
};

struct GroupTag {};
/// Generational handle of a group (zero = null; a stale handle never resolves).
using GroupId = core::Handle<GroupTag>;

/// A read-only view of one group (for viewers, the server, tests).
struct GroupInfo {
  std::uint32_t id = 0;                ///< stable group id (spawn order of groups)
  std::uint32_t population = 0;        ///< index into ScenarioDesc::populations
  std::vector<std::uint32_t> members;  ///< stable ids of members present, ascending
  std::uint32_t leader = 0xffffffffu;  ///< stable id of the leader (0xffffffff when none present)
  std::uint32_t goalIndex = 0;         ///< position in the goal list the group is heading for
  std::uint32_t goalPoint = 0xffffffffu;  ///< index of that point in ScenarioDesc::points, or none
  bool waiting = false;                ///< members are waiting at a goal for the others
  bool guided = false;                 ///< following a dynamic goal (guide)
  core::Vec2 guide;                    ///< the guide's position while guided
  bool following = false;              ///< adopting another group's goals right now
  std::uint32_t followedGroup = 0xffffffffu;
};

/// What one agent is doing, for a viewer's "who is this" panel (the server's /api/agent).
struct AgentInfo {
  std::uint32_t id = 0;                 ///< stable id
  std::uint32_t group = 0;              ///< stable group id
  std::uint32_t population = 0;         ///< index into ScenarioDesc::populations
  AgentMode mode = AgentMode::Waiting;
  /// "walking to its goal", "at an action point", "waiting for its group", "playing a Common Ground
  /// script", "done", "left".
  std::string state;
  core::Vec2 position, target;          ///< where it is and where it heads [m]
  float height = 0.0f, targetHeight = 0.0f;  ///< their floor heights [m] (0 on a flat world)
  std::uint32_t goalPoint = 0xffffffffu;  ///< index into ScenarioDesc::points of its current goal, or none
  std::uint16_t clip = 0;               ///< motion clip playing (animationClips)
  float speed = 0.0f;                   ///< desired walking speed [m/s]
  std::uint32_t coordination = 0xffffffffu;  ///< Common Ground coordination it plays a script in, or none
  std::uint32_t followedAgent = 0xffffffffu; ///< sociological model: the agent it follows, or none
  bool guided = false;                  ///< its group follows a guide
};

/// Most agents one crowd insertion may add (groups × largest group size, summed).
inline constexpr std::uint64_t kMaxInsertAgents = 10000;
/// Most agents all insertions into one world may add together, over the whole run.
inline constexpr std::uint64_t kMaxInsertedAgents = 200000;

/// An inserted crowd as the World sees it (World::crowds).
struct CrowdInfo {
  std::string id;
  std::uint32_t index = 0;            ///< insertion order (what insertCrowd returned)
  bool applied = false;               ///< inserted at the start of a tick (false: still queued)
  bool removed = false;               ///< removeCrowd took effect: its agents left
  std::uint64_t insertTick = 0;       ///< tick it was applied at (valid when applied)
  std::uint32_t firstPopulation = 0;  ///< its populations: [first, first + populations) of desc().populations
  std::uint32_t populations = 0;
  std::uint32_t firstPoint = 0;       ///< its points: [first, first + points) of desc().points
  std::uint32_t points = 0;
  std::uint32_t firstGroup = 0;       ///< its groups' stable ids: [first, first + groups)
  std::uint32_t groups = 0;
  std::uint32_t present = 0;          ///< its agents in the world now
};

/// The agents present, read in place from the World's own columns (no copy): row i of every span is
/// the i-th agent in ascending stable-id order, as in a Frame. Valid until the World changes (the
/// next step(), which spawns, moves and removes agents; commands wait for it); see
/// World::keepRetiredColumns for how long the memory itself lives.
struct AgentColumns {
  std::span<const std::uint32_t> id;     ///< stable spawn-order ids: ascending, unless the world sorts its rows spatially (ScenarioDesc::rowOrder)
  std::span<const std::uint32_t> group;  ///< stable group id
  std::span<const float> posX, posY;     ///< [m]
  std::span<const float> posZ;           ///< height [m] on a multi-level world; empty on a flat one
  std::span<const float> velX, velY;     ///< [m/s]
  std::span<const float> oriX, oriY;     ///< unit heading
  std::span<const AgentMode> mode;
  std::span<const std::uint16_t> clip;   ///< motion clip playing (animationClips)
  std::span<const float> phase;          ///< position in that clip, [0, 1)

  [[nodiscard]] std::size_t size() const { return id.size(); }
};

/// Receives each phase's duration; the app passes one in (the core reads no clock itself).
class PhaseObserver {
 public:
  virtual ~PhaseObserver() = default;
  virtual void phaseBegin(std::string_view phase) = 0;
  virtual void phaseEnd(std::string_view phase) = 0;
};

class World {
 public:
  /// Builds a world from a validated description. `navmesh` may be passed when the loader already
  /// built it (for validation); otherwise it is built here.
  static core::Result<std::unique_ptr<World>> create(const ScenarioDesc& desc,
                                                     std::shared_ptr<const nav::NavMesh> navmesh = nullptr);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances one tick of dt seconds. Threads come from `tasks`; the result does not depend on them.
  void step(const core::TaskSystem& tasks, PhaseObserver* observer = nullptr);

  /// Shares the steer phase with the other copies of this world behind `exchange` (one per rank,
  /// each created from the same description; partition.hpp). The result stays bit-identical to
  /// one process. nullptr switches it off. The exchange must outlive the world's use of it, and
  /// every rank must set it before the same tick.
  void setPartition(StepExchange* exchange, PartitionOptions options = {});
  /// This rank's share of the work since setPartition (zeros when never set).
  [[nodiscard]] const PartitionStats& partitionStats() const;

  // Groups and crowd control (Musse et al. §3.2.6). Commands are queued and applied at the start
  // of the next tick in the order they were given, so they never race with a tick.

  /// Handle of group `index` (0-based) of the population with id `population`; null if none.
  [[nodiscard]] GroupId group(std::string_view population, std::uint32_t index) const;
  /// Handle of the group with stable id `id`; null if none.
  [[nodiscard]] GroupId groupById(std::uint32_t id) const;
  [[nodiscard]] std::optional<GroupInfo> groupInfo(GroupId group) const;
  [[nodiscard]] std::size_t groupCount() const;
  /// The agent with stable id `id`, if present.
  [[nodiscard]] std::optional<AgentInfo> agentInfo(std::uint32_t id) const;
  /// The group becomes guided: `position` (an avatar's, say) is its dynamic goal until released.
  /// Returns false for a stale or null handle.
  bool guide(GroupId group, core::Vec2 position);
  /// The same on a multi-level world: `height` [m] is the floor the guide stands on.
  bool guide(GroupId group, core::Vec2 position, float height);
  /// Guidance ends; the group resumes its own goals where it left them.
  bool release(GroupId group);
  /// Queues a crowd (validated by io::parseCrowd against this world) for the start of the next
  /// tick: its points and populations are appended to desc(), its groups get the next group ids,
  /// its agents the next agent ids as they spawn; population start times count from that tick.
  /// Refused, with nothing changed, when its id, a population id or a point id is already taken
  /// (queued crowds included), an index is out of range, a body radius exceeds the navmesh's
  /// erosion radius, an action point plays an action the world has no clip for, or the agents
  /// exceed kMaxInsertAgents or, with the earlier insertions, kMaxInsertedAgents. Returns the
  /// crowd's index (insertion order). Deterministic: the same insertions before the same ticks
  /// give the same trajectories for any thread count.
  core::Result<std::uint32_t> insertCrowd(const CrowdDesc& crowd);
  /// Queues the removal of crowd `id`: at the start of the next tick its agents leave (an Exit
  /// event with a = 0xffffffff, b = the crowd's index) and its populations spawn nobody more.
  /// Its points, groups and ids stay taken. False when no crowd has that id or it is removed.
  bool removeCrowd(std::string_view id);
  /// Queues the removal of the agents with these stable ids for the start of the next tick (before
  /// anyone spawns), in the order given: each leaves as a removed crowd's agents do — an Exit event
  /// with a = b = 0xffffffff, counted in stats().removed — and its group goes on with the others (a
  /// leader removed hands over to the lowest id left, as on an exit). Refused with nothing queued,
  /// one diagnostic per bad id (pointer "/<index in ids>"), when an id is not an agent present now,
  /// is listed twice or is already queued.
  core::Status removeAgents(std::span<const std::uint32_t> ids);
  /// Queues closing (`open` false) or opening exit `pointId` for the start of the next tick, as a
  /// timeline "close" / "open" entry does — for doors that open and close on events the caller
  /// sees (a train arriving, an alarm): nobody leaves through a closed exit (whoever reaches it
  /// waits there), and exit choice sends the groups heading for it to another at once. False when
  /// no point of kind exit has that id (a queued crowd's points count once it is applied).
  bool setExitOpen(std::string_view pointId, bool open);
  /// Whether closing exit `pointId` makes its floor a wall (docs/crowd-model.md "A closed exit is a
  /// wall"): true for every exit with floor in its region. The navmesh is cut for the scenario's
  /// exits and those of the crowds its timeline inserts when it is built; an exit of a crowd
  /// insertCrowd brought is cut when the first such exit closes, on a mesh built again from the
  /// description in the background from when the crowd was applied (the tick that closes it waits
  /// for that build when it is not done yet). False for an exit with no floor
  /// in its region, for one not cut yet when the description holds no geometry to build the mesh
  /// again from (a mesh handed to create), and when no point of kind exit has that id.
  [[nodiscard]] bool exitIsWall(std::string_view pointId) const;
  /// Every crowd inserted or queued, in insertion order (timeline crowds included).
  [[nodiscard]] std::vector<CrowdInfo> crowds() const;
  /// Viewer positions for multiresolution steering (SteeringDesc::lodDistance).
  void setViewers(std::vector<core::Vec2> viewers);

  /// Takes the frame of this tick: the current state plus the events, Common Ground script entries
  /// and finished coordinations since the previous call, which are drained (call it once per tick
  /// you want to keep, or lose those events).
  [[nodiscard]] FramePtr takeFrame();

  /// The agents' columns as they are now, without a copy (takeFrame copies them). Takes and drains nothing.
  [[nodiscard]] AgentColumns agentColumns() const;
  /// While on, memory read through agentColumns is never freed by the World: when its columns must
  /// grow (agents beyond the capacity reserved for the scenario, e.g. inserted crowds), they move to
  /// new buffers together and the old ones are kept for takeRetiredColumns instead of freed. For
  /// readers that cannot be told when to stop reading (the Python module's numpy views); off by
  /// default. The values are the same either way.
  void keepRetiredColumns(bool on);
  /// The buffers retired since the last call (see keepRetiredColumns): the caller frees them by
  /// dropping the handles, once nothing reads them any more.
  [[nodiscard]] std::vector<std::shared_ptr<const void>> takeRetiredColumns();

  /// True when nothing is left to simulate: every agent spawned has exited and none is scheduled
  /// (only when the scenario has exits or finite goals; wandering crowds never finish).
  [[nodiscard]] bool finished() const;

  [[nodiscard]] const WorldStats& stats() const;
  [[nodiscard]] const ScenarioDesc& desc() const;
  [[nodiscard]] const nav::NavMesh& navMesh() const;
  /// FNV-1a hash of the bit patterns of every agent's id, position and velocity, in id order
  /// (determinism tests compare it across thread counts).
  [[nodiscard]] std::uint64_t stateHash() const;

 private:
  World();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::sim

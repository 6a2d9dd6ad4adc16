// AgentStore — the agents' hot data as structure of arrays: one dense row per agent present, in
// ascending stable-id order until the World sorts them spatially (ScenarioDesc::rowOrder, permute;
// new agents get the next id and are appended; removal is a stable compaction in the emit phase).
// Phases read columns and write only their own row.
// The published columns (World::agentColumns) can be kept from being freed while zero-copy readers
// hold them (keepRetired).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "compact_lists.hpp"
#include "throng/core/assert.hpp"
#include "throng/core/vec2.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"
#include "throng/sim/frame.hpp"

namespace throng::sim {

/// Where an agent is in its goal list.
enum class GoalState : std::uint8_t {
  Seeking = 0,  ///< walking to the current goal's target
  Acting = 1,   ///< stopped at an action point until actionEndTick
  Done = 2,     ///< every goal visited, nothing more to do
  Exited = 3,   ///< reached an exit: removed in this tick's emit phase
  WaitingForGroup = 4,  ///< at its group's goal, waiting until the others arrive (flocking rule 4)
  Scripted = 5,  ///< playing its action script of a Common Ground coordination (common_ground_play.cpp)
  PreMovement = 6,  ///< present and standing until its pre-movement time ends at actionEndTick (spawn.cpp)
  Incapacitated = 7,  ///< its toxic dose reached its population's limit: stands where it fell for good (decide.cpp)
  Riding = 8,  ///< at a lift's or escalator's stop: queuing or carried (vertical_transport.cpp), not walking
};

inline constexpr std::uint16_t kNoClip = 0xffff;

/// Busy with a target of its own (an action point's stop, a Common Ground script) or not started
/// yet (pre-movement): group-level retargeting (guidance, following) leaves the agent alone; it
/// rejoins its group when done.
[[nodiscard]] inline bool holdsOwnTarget(GoalState s) {
  return s == GoalState::Acting || s == GoalState::Scripted || s == GoalState::PreMovement || s == GoalState::Incapacitated ||
         s == GoalState::Riding;
}

/// "None" for a stable agent id.
inline constexpr std::uint32_t kNoAgent = 0xffffffffu;
/// "None" for a stable group id.
inline constexpr std::uint32_t kNoGroup = 0xffffffffu;
/// "None" for a point index (ScenarioDesc::points), as the recorded events write it.
inline constexpr std::uint32_t kNoPoint = 0xffffffffu;
/// "None" for a row of the AgentStore (World::Impl::rowOfId of an agent gone).
inline constexpr std::uint32_t kNoRow = 0xffffffffu;
/// "None" for an index into a side table (GroupState::extra, GroupExtra::route) or a coordination id.
inline constexpr std::uint32_t kNoIndex = 0xffffffffu;

/// A goal change decide asks the group pass for (target draws are serial).
enum class GoalPending : std::uint8_t {
  None = 0,
  NextGoal = 1,          ///< go on to the next goal of the list
  NextWanderTarget = 2,  ///< wandering: draw the next random target
};

/// What meeting an agent of another group did to this one (sociological model, decide → group pass).
enum class SocialEffect : std::uint8_t {
  None = 0,
  JoinGroup = 1,    ///< joins the other agent's group
  FollowAgent = 2,  ///< follows the other agent for a while
};

/// Columns are grouped by the features that use them. The optional groups exist (have one entry per
/// row) only when the scenario can use them; otherwise they stay empty and the accessors below
/// return the defaults, so lone agents of a plain scenario pay nothing for features they never use
/// (docs/performance.md, "Memory per agent").
struct AgentStore {
  // Identity.
  std::vector<std::uint32_t> id;          ///< stable spawn-order id
  std::vector<std::uint32_t> group;       ///< stable group id
  std::vector<std::uint16_t> population;  ///< index into ScenarioDesc::populations
  std::vector<std::uint16_t> groupSize;   ///< size of its group (head-on priority in steer; no group lookup there)
  // Kinematics [m], [m/s].
  std::vector<float> posX, posY, velX, velY;
  std::vector<float> prefVelX, prefVelY;  ///< written by steer: the preferred (desired) velocity, not yet relaxed
  std::vector<float> newVelX, newVelY;    ///< written by steer (ORCA result), committed by integrate
  std::vector<std::uint8_t> holdHeading;  ///< written by steer (the model): 1 keeps the heading this tick
  /// written by steer (avm): the look ahead's last choice, a turn of that many 15° steps from the
  /// desired direction, kept between looks (anticipation_velocity_model.cpp, kLookPeriod)
  std::vector<std::int8_t> lookTurn;
  std::vector<float> oriX, oriY;          ///< unit heading
  std::vector<float> radius;              ///< body radius [m]
  std::vector<float> speed;               ///< desired walking speed [m/s]
  std::vector<AgentMode> mode;
  // Goals and navigation.
  std::vector<GoalState> goalState;
  std::vector<std::uint32_t> goalCursor;  ///< index into the population's goals; == size: past the last
  std::vector<float> targetX, targetY;    ///< where the agent is heading inside the goal region
  std::vector<std::uint32_t> targetDraws; ///< how many targets drawn (feeds the target RNG stream)
  std::vector<std::uint8_t> needPath;     ///< decide asks plan for a new path
  std::vector<nav::PathTicket> ticket;    ///< pending path request, 0 = none
  /// Navmesh polygon under the agent. Detour's references are 32-bit in Debian's build (no
  /// DT_POLYREF64); integrate checks that every reference it gets back fits.
  std::vector<std::uint32_t> polyRef;
  std::vector<CornerPath> corners;        ///< string-pulled path and the corner walked to (2 inline)
  /// Tick the action (Acting) or the pre-movement wait (PreMovement) ends. 32 bits: a world runs at
  /// most 2^32 ticks (6.8 years at dt = 0.05 s).
  std::vector<std::uint32_t> actionEndTick;
  std::vector<float> progressDistance;    ///< distance to target at the last progress check [m]
  std::vector<float> stuckTime;           ///< how long the agent has wanted to walk but barely moved [s]
  std::vector<std::uint8_t> dynamicTarget; ///< target set by a guide or a followed agent: approached slowing down
  std::vector<GoalPending> goalPending;  ///< decide → group pass
  std::vector<std::int32_t> targetSub;    ///< sub-region holding the target (index into pointSubOffset space), -1 none
  std::vector<std::uint16_t> animClip;    ///< motion clip playing (animation.hpp)
  std::vector<float> animPhase;           ///< its phase in [0, 1)
  // Toxicity (only when some smoke region has carbon monoxide: SmokeDesc::co).
  bool toxic = false;
  std::vector<float> dose;  ///< fractional effective dose taken up so far (coDosePerSecond) [1]
  // Levels (only on a multi-level world: ScenarioDesc::terrain, a layered navmesh).
  bool levels = false;
  std::vector<float> posZ;     ///< height of the floor under the agent [m] (from its navmesh polygon)
  std::vector<float> targetZ;  ///< height of the floor the target is on [m]: picks the level for paths
  /// Height of the floor each of `corners` is on [m], as plan found the path (empty when the corners
  /// came from elsewhere: a Bézier path); a walker off the height its path has where it stands
  /// re-plans (decide.cpp, checkFloor).
  std::vector<std::vector<float>> cornerZ;
  // Formation (only when some population has flocking groups of two or more).
  bool formation = false;
  std::vector<float> formVelX, formVelY;  ///< formation correction from the group pass [m/s]
  // Sociological model (only when some population has it on).
  bool sociological = false;
  std::vector<std::uint32_t> followAgent; ///< stable id of the agent followed, kNoAgent if none
  std::vector<std::uint32_t> followUntil; ///< tick that following ends (32 bits, as actionEndTick)
  std::vector<SocialEffect> sociologicalEffect; ///< decide → group pass (the other agent in sociologicalOther)
  std::vector<std::uint32_t> sociologicalOther; ///< the agent met
  // Common Ground (common_ground*.cpp; only when the scenario's social section is on).
  bool commonGround = false;
  std::vector<std::uint32_t> coordination;  ///< id of the coordination it plays a script in, kNoIndex if none
  std::vector<std::uint8_t> scriptWalk;     ///< while Scripted: 1 = walking to its target, 0 = standing
  std::vector<std::uint16_t> scriptClip;    ///< while Scripted: animation clip played, kNoClip = walk/idle by motion
  std::vector<std::uint32_t> desirePoint;   ///< decide → group pass: generated goal (point), kNoPoint if none
  std::vector<std::uint8_t> desireTrigger;  ///< its GoalTrigger
  std::vector<std::uint32_t> socialReady;   ///< first tick a new goal may be generated (cooldown; 32 bits)
  std::vector<std::uint64_t> interests;     ///< bit c: interested in category c (World::Impl::categories)
  std::vector<std::vector<std::uint32_t>> visited;  ///< cold: points visited through the goal generator
  // Neighbours found by sense: row indices, maxNeighbours slots per agent.
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> neighbourCount;

  [[nodiscard]] std::size_t size() const { return id.size(); }

  // Optional columns read as their defaults when absent.
  [[nodiscard]] core::Vec2 formVel(std::size_t row) const {
    return formation ? core::Vec2{formVelX[row], formVelY[row]} : core::Vec2{};
  }
  /// Writes the formation correction (a zero needs no column).
  void setFormVel(std::size_t row, float x, float y) {
    if (formation) {
      formVelX[row] = x;
      formVelY[row] = y;
    }
  }
  [[nodiscard]] float height(std::size_t row) const { return levels ? posZ[row] : 0.0f; }
  [[nodiscard]] float targetHeight(std::size_t row) const { return levels ? targetZ[row] : 0.0f; }
  void setTargetHeight(std::size_t row, float z) {
    if (levels) targetZ[row] = z;
  }
  /// The target is the agent's own position (standing still, waiting).
  void targetSelf(std::size_t row) {
    targetX[row] = posX[row];
    targetY[row] = posY[row];
    if (levels) targetZ[row] = posZ[row];
  }
  /// Whether height z is on the agent's level (always on a flat world).
  [[nodiscard]] bool sameLevel(std::size_t row, float z) const {
    return !levels || std::abs(posZ[row] - z) < kSameLevel;
  }
  /// Height difference [m] below which two things are on the same level (a step is 0.35 m at most;
  /// floors are 2 m or more apart).
  static constexpr float kSameLevel = 1.2f;
  /// The height of the floor corner k of the row's path is on [m]; NaN when not known (a flat world,
  /// or corners that did not come from plan).
  [[nodiscard]] float cornerHeight(std::size_t row, std::uint32_t k) const {
    if (!levels) return std::numeric_limits<float>::quiet_NaN();
    const std::vector<float>& z = cornerZ[row];
    return z.size() == corners[row].size() && k < z.size() ? z[k] : std::numeric_limits<float>::quiet_NaN();
  }
  [[nodiscard]] std::uint32_t followedAgent(std::size_t row) const { return sociological ? followAgent[row] : kNoAgent; }
  [[nodiscard]] std::uint32_t coordinationOf(std::size_t row) const { return commonGround ? coordination[row] : kNoIndex; }
  [[nodiscard]] bool scriptWalking(std::size_t row) const { return commonGround && scriptWalk[row] != 0; }
  [[nodiscard]] std::uint16_t scriptClipOf(std::size_t row) const { return commonGround ? scriptClip[row] : kNoClip; }

  /// Applies f to every per-agent column present (not the neighbour buffers, which sense rebuilds).
  template <class F>
  void forEachColumn(F&& f) {
    f(id); f(group); f(population); f(groupSize);
    f(posX); f(posY); f(velX); f(velY); f(prefVelX); f(prefVelY); f(newVelX); f(newVelY); f(holdHeading); f(lookTurn);
    f(oriX); f(oriY); f(radius); f(speed); f(mode);
    f(goalState); f(goalCursor); f(targetX); f(targetY); f(targetDraws); f(needPath); f(ticket); f(polyRef);
    f(corners); f(actionEndTick); f(progressDistance); f(stuckTime);
    f(animClip); f(animPhase); f(goalPending); f(targetSub); f(dynamicTarget);
    if (levels) { f(posZ); f(targetZ); f(cornerZ); }
    if (toxic) f(dose);
    if (formation) { f(formVelX); f(formVelY); }
    if (sociological) { f(followAgent); f(followUntil); f(sociologicalEffect); f(sociologicalOther); }
    if (commonGround) {
      f(coordination); f(scriptWalk); f(scriptClip); f(desirePoint); f(desireTrigger); f(socialReady); f(interests);
      f(visited);
    }
  }

  /// Applies f to every column World::agentColumns publishes (zero-copy readers: the Python module).
  template <class F>
  void forEachPublishedColumn(F&& f) {
    f(id); f(group); f(posX); f(posY); f(velX); f(velY); f(oriX); f(oriY); f(mode); f(animClip); f(animPhase);
    if (levels) f(posZ);
  }

  /// While set (World::keepRetiredColumns), a published column is never freed under a reader: when
  /// one must grow, every published column moves to a new buffer together and the old buffers go to
  /// `retired` (World::takeRetiredColumns hands them out) instead of being freed.
  bool keepRetired = false;
  std::vector<std::shared_ptr<const void>> retired;

  /// Appends one default-initialised row and returns its index.
  std::size_t addRow() {
    if (keepRetired && id.size() == minPublishedCapacity()) retirePublished();
    forEachColumn([](auto& column) { column.emplace_back(); });
    return size() - 1;
  }

  /// The smallest capacity of the published columns (a row more than that reallocates one).
  [[nodiscard]] std::size_t minPublishedCapacity() {
    std::size_t c = SIZE_MAX;
    forEachPublishedColumn([&](auto& column) { c = std::min(c, column.capacity()); });
    return c;
  }
  /// Moves every published column's buffer to `retired` and continues in a copy with room to grow.
  void retirePublished() {
    const std::size_t capacity = std::max<std::size_t>(64, 2 * size());
    forEachPublishedColumn([&](auto& column) {
      using Column = std::decay_t<decltype(column)>;
      auto old = std::make_shared<Column>(std::move(column));  // the buffer itself moves: readers keep their memory
      column = Column();
      column.reserve(capacity);
      column.assign(old->begin(), old->end());
      retired.push_back(std::move(old));
    });
  }

  /// Puts the rows in the order `keys` gives: new row i is old row (the low 32 bits of) keys[i],
  /// a permutation of [0, size()). Every column keeps its buffer (the published ones too). Columns
  /// of plain values of up to 8 bytes go through `scratch` (at least 4 · size() bytes) four bytes
  /// of each value at a time and are gathered back; the others (paths, visited lists) are moved in
  /// place, one cycle of the permutation at a time.
  void permute(std::span<const std::uint64_t> keys, std::span<std::byte> scratch) {
    const std::size_t n = keys.size();
    THRONG_ASSERT(scratch.size() >= 4 * n);
    const auto from = [&](std::size_t i) { return static_cast<std::uint32_t>(keys[i]); };
    std::vector<bool> done;
    forEachColumn([&](auto& column) {
      using T = typename std::decay_t<decltype(column)>::value_type;
      if constexpr (std::is_trivially_copyable_v<T> && sizeof(T) <= 8) {
        constexpr std::size_t lane = std::min<std::size_t>(sizeof(T), 4);
        static_assert(sizeof(T) % lane == 0);
        auto* bytes = reinterpret_cast<unsigned char*>(column.data());
        auto* held = reinterpret_cast<unsigned char*>(scratch.data());
        for (std::size_t at = 0; at < sizeof(T); at += lane) {  // a lane: bytes [at, at + lane) of each value
          for (std::size_t i = 0; i < n; ++i) std::memcpy(held + i * lane, bytes + i * sizeof(T) + at, lane);
          for (std::size_t i = 0; i < n; ++i) std::memcpy(bytes + i * sizeof(T) + at, held + from(i) * lane, lane);
        }
      } else {
        done.assign(n, false);
        for (std::size_t start = 0; start < n; ++start) {
          if (done[start]) continue;
          // The cycle start ← from(start) ← from(from(start)) ← …: each row takes its source's value.
          T held = std::move(column[start]);
          std::size_t i = start;
          for (;;) {
            done[i] = true;
            const std::size_t source = from(i);
            if (source == start) break;
            column[i] = std::move(column[source]);
            i = source;
          }
          column[i] = std::move(held);
        }
      }
    });
  }

  /// Keeps rows whose keep[row] is non-zero, in order.
  void compact(const std::vector<std::uint8_t>& keep) {
    forEachColumn([&](auto& column) {
      std::size_t w = 0;
      for (std::size_t r = 0; r < column.size(); ++r) {
        if (keep[r]) {
          if (w != r) column[w] = std::move(column[r]);
          ++w;
        }
      }
      column.resize(w);
    });
  }
};

}  // namespace throng::sim

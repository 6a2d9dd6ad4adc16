// GroupTable — every social group of the world (Musse et al. §3.1.2: a crowd is a set of groups),
// indexed by stable group id, with the cold parts only some groups need (waiting, formation,
// Common Ground: GroupExtra), their guidance and following (GroupRoute), and the busy set the group
// pass visits every tick. Groups are never removed, so a group's handle is {id + 1, generation 1}.
// Written by spawning, run-time insertion and the serial group pass; read by every phase.
#pragma once
#include <cstdint>
#include <vector>

#include "agent_store.hpp"
#include "compact_lists.hpp"
#include "throng/core/assert.hpp"
#include "throng/core/vec2.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// Guidance and following of a group (§3.2.6, §3.2.5): only groups with a guide script, guided
/// through the API, or following another group have one (GroupTable::routeFor).
struct GroupRoute {
  core::Vec2 guide;
  float guideHeight = 0.0f;  ///< floor height of the guide [m] (multi-level worlds)
  core::Vec2 guidePlanned{1e30f, 1e30f};  ///< guide position the members' paths were planned for
  std::uint32_t followGroup = kNoGroup;  ///< group followed while `following`
  std::uint32_t followToggle = 0;        ///< tick the current (temporary) period ends (32 bits, as actionEndTick)
  std::uint32_t ownCursor = 0;           ///< own cursor saved while following temporarily
  bool guidedByApi = false;
};

/// The part of a group that lone agents never need: waiting, formation shape, Common Ground. Only
/// groups that may need it have one (GroupTable::extraOf): busy groups (GroupState::busy)
/// and, when Common Ground is on, every group. Others read the defaults.
struct GroupExtra {
  // Formation.
  core::Vec2 centroid, heading{1.0f, 0.0f};
  // Waiting (flocking rule 4).
  std::uint32_t waitStart = 0;           ///< tick the wait began (32 bits, as actionEndTick)
  // Common Ground (common_ground.cpp).
  std::uint32_t coordination = kNoIndex;  ///< id of the coordination its members play now
  std::uint32_t reunite = kNoIndex;       ///< a divide ended: id of that coordination until the group is whole again
  std::uint32_t route = kNoIndex;         ///< index into the table's routes, kNoIndex: none
  bool waiting = false;
};

/// One social group (Musse et al. §3.1.2: a crowd is a set of groups), indexed by the stable group
/// id; written only by the serial group pass (groups.cpp) and by spawning. 40 bytes: what every
/// group, even a lone agent's, needs; the rest is in its GroupExtra, if it has one. The shared
/// walking speed of a flocking group is drawn again when needed (groupSpeed, group_pass.hpp).
struct GroupState {
  MemberList members;                  ///< stable ids present in the world, ascending
  std::uint32_t expected = 0;          ///< members that will be spawned
  std::uint32_t leader = kNoAgent;
  std::uint32_t goalList = 0;          ///< own goal list: index into World::Impl::goalLists
  std::uint32_t cursor = 0;            ///< goal the group is heading for (index into the active list)
  std::uint32_t extra = kNoIndex;      ///< index into the table's cold parts, kNoIndex: none
  std::uint16_t population = 0;
  bool busy : 1 = false;               ///< visited by the group pass every tick (GroupTable::busy)
  bool guided : 1 = false;             ///< guidance (§3.2.6) on: read by every member in decide
  bool following : 1 = false;          ///< following another group (§3.2.5) now: read by activeGoals

  [[nodiscard]] bool flocks(const PopulationDesc& pop) const { return pop.flocking && expected >= 2; }
};
static_assert(sizeof(GroupState) <= 40);

class GroupTable {
 public:
  [[nodiscard]] std::uint32_t size() const { return static_cast<std::uint32_t>(groups_.size()); }
  [[nodiscard]] GroupState& operator[](std::uint32_t gid) { return groups_[gid]; }
  [[nodiscard]] const GroupState& operator[](std::uint32_t gid) const { return groups_[gid]; }
  [[nodiscard]] auto begin() const { return groups_.begin(); }
  [[nodiscard]] auto end() const { return groups_.end(); }
  /// Appends a group; returns its stable id.
  std::uint32_t add(GroupState g);
  void reserve(std::size_t groups, std::size_t extras);

  /// Puts the group in the busy set (from the next refreshBusy) and gives it a cold part.
  void markBusy(std::uint32_t gid);
  /// Gives the group a cold part without making it busy (Common Ground may start a coordination in
  /// any group).
  void giveExtra(std::uint32_t gid);
  /// The group's cold part (the defaults when it has none). The reference is invalidated by markBusy.
  [[nodiscard]] const GroupExtra& extraOf(const GroupState& g) const {
    static const GroupExtra kNone;
    return g.extra == kNoIndex ? kNone : extras_[g.extra];
  }
  /// The cold part of a busy group (or, with Common Ground on, of any group): it always has one.
  [[nodiscard]] GroupExtra& extraOf(GroupState& g) {
    THRONG_ASSERT(g.extra != kNoIndex);
    return extras_[g.extra];
  }
  /// The group's guidance and following state (the defaults when it has none).
  [[nodiscard]] const GroupRoute& routeOf(const GroupState& g) const {
    static const GroupRoute kNone;
    const std::uint32_t r = extraOf(g).route;
    return r == kNoIndex ? kNone : routes_[r];
  }
  /// The group's guidance and following state, created on first use (marks the group busy). The
  /// reference is invalidated by the next routeFor.
  GroupRoute& routeFor(std::uint32_t gid);
  [[nodiscard]] bool hasRoute(const GroupState& g) const { return extraOf(g).route != kNoIndex; }

  /// Groups the group pass visits (GroupState::busy), ascending, as of the last refreshBusy: flocking
  /// groups of 2+, guided, following or followed, or sociable ones. Lone agents with none of these
  /// need no per-tick group work. Groups made busy during a pass join at the next refresh.
  [[nodiscard]] const std::vector<std::uint32_t>& busy() const { return busy_; }
  /// Rebuilds the busy set when groups were made busy since the last refresh.
  void refreshBusy();

 private:
  std::vector<GroupState> groups_;
  std::vector<GroupExtra> extras_;   ///< cold parts, see GroupExtra
  std::vector<GroupRoute> routes_;   ///< see GroupRoute
  std::vector<std::uint32_t> busy_;  ///< ascending
  bool busyDirty_ = true;
};

}  // namespace throng::sim

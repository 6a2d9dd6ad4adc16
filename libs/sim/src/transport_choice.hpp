// TransportRoutes — people choosing a lift, an escalator or their own feet (docs/crowd-model.md,
// "Choosing a lift, an escalator or the stairs"). When a group of a population with
// PopulationDesc::useTransports sets off for a goal that is no transport's stop, its first member
// to do so weighs walking there against every way by the scenario's lifts and escalators, in
// seconds: walking to a boarding stop, the wait there as things stand (VerticalTransports::
// expectedWait), the ride (rideTime), and from the stop it rides to, walking on to the goal or
// taking a further transport (a shortest-time search over the stops). When riding is quicker, the
// boarding stop goes into the group's own goal list before the goal (GoalWriter::routeByTransport),
// so the rest — queuing, being carried, going on to the goal — is VerticalTransports' as for a stop a
// scenario names. Distances are walking distances on the navmesh (nav::DistanceField per stop, built
// at creation, and per goal, built when first weighed; stairs priced as in exit choice); each group
// decides each of its goals once. Serial (setGoal's callers): the same for any thread or rank count.
// When a door closes or opens (meshChanged), a field is measured anew the next time a decision
// reads it: the stops' at the next decision, a goal's when a group next weighs the way there.
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "agent_store.hpp"
#include "throng/nav/distance_field.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

class VerticalTransports;

class TransportRoutes {
 public:
  /// The fields of every transport stop and the walking distances between the stops, when the
  /// scenario has transports and a population that uses them; nothing otherwise. A goal's field is
  /// built when a group first weighs the way there (boardingFor), so creation costs what the stops
  /// cost, whatever the number of points. `mesh` must outlive this.
  void prepare(const ScenarioDesc& desc, const nav::NavMesh& mesh, const nav::NavQuery& query);
  [[nodiscard]] bool active() const { return !stops_.empty(); }
  /// A door's polygons closed or opened on the mesh prepare() was given (World::closeDoorFloor):
  /// every field is stale, and rebuilt when next read (fieldOf, measureStops).
  void meshChanged();

  /// Whether group `gid` has not decided how to reach the goal at `cursor` of its list yet; marks it
  /// decided (the first member to set off for it decides for the group).
  bool claim(std::uint32_t gid, std::uint32_t cursor);

  /// The boarding stop (a point index) agent `row` should walk to on its way to point `goal`, or
  /// kNoIndex when walking is as quick. `heading(point)`: how many people target that point now
  /// (queuing, on their way or carried from it). `rideIfAny`: the quickest ride whatever walking
  /// takes (someone who does not take the stairs: PopulationDesc::stairClimbUp), kNoIndex only when
  /// no ride reaches the goal. Builds `goal`'s field the first time.
  [[nodiscard]] std::uint32_t boardingFor(const ScenarioDesc& desc, const AgentStore& a, std::size_t row, std::uint32_t goal,
                                          const VerticalTransports& transports,
                                          const std::function<std::uint32_t(std::uint32_t)>& heading, bool rideIfAny = false);

  /// The goal list group `gid` owns for its rides (index + 1 into the world's goal lists; 0: none yet).
  std::uint32_t& ownList(std::uint32_t gid);

 private:
  /// A stop of a transport, and where it is on the navmesh.
  struct Stop {
    std::uint32_t point = 0, transport = 0, index = 0;  ///< its point, transport, index in that transport's stops
    core::Vec2 p;
    nav::PolyRef ref = 0;
    bool boards = false;  ///< people step on here (an escalator's foot, any stop of a lift)
  };
  /// The field of `point`, built now if it was not or the mesh changed since (null: no such point).
  const nav::DistanceField* fieldOf(const ScenarioDesc& desc, std::uint32_t point);
  /// The stops' fields and the walking distances between the stops, on the mesh as it is now.
  void measureStops(const ScenarioDesc& desc);

  const nav::NavMesh* mesh_ = nullptr;
  nav::DistanceFieldConfig config_;
  std::deque<nav::DistanceField> fields_;  ///< a deque: built on demand, earlier ones stay where they are
  std::vector<std::int32_t> fieldOfPoint_;  ///< point → index into fields_, -1: none
  std::vector<std::uint64_t> fieldVersion_;  ///< per field: meshVersion_ when it was built
  std::uint64_t meshVersion_ = 0;   ///< doors closed or opened so far (meshChanged)
  std::uint64_t stopsVersion_ = 0;  ///< meshVersion_ when the stops were measured (measureStops)
  std::vector<Stop> stops_;
  std::vector<float> between_;  ///< walking distance from stop i to stop j: between_[i * stops + j] [m]
  std::vector<std::uint32_t> decided_;  ///< per group: 1 + the last goal cursor decided
  // boardingFor's working space, per stop (kept between calls: no allocation per decision).
  std::vector<std::size_t> dest_;  ///< where boarding there takes one (index into stops_; stops_.size(): nowhere)
  std::vector<float> leg_;         ///< waiting and riding from there [s]
  std::vector<float> onward_;      ///< from stepping off there to the goal [s]
  std::vector<std::uint32_t> ownList_;  ///< per group: see ownList()
};

}  // namespace throng::sim

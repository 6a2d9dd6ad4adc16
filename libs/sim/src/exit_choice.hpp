// exit_choice — the tactical layer's exit choice (docs/crowd-model.md "Tactical level: exit
// choice"): a population that names several "exits" lets each of its groups walk, after its goals,
// to one of them, chosen by a rule — the nearest by walking distance, the quickest (walking time
// plus the queue ahead at the exit over its capacity, re-evaluated every period with hysteresis),
// or a fixed allocation by shares — and to another one when its exit closes (the timeline's
// "close"). World::Impl owns one ExitChoice; its parts:
//   - a nav::DistanceField per exit some population chooses among (built at creation and when a
//     crowd brings new ones, rebuilt round the closed doors when a door closes or opens), so every
//     distance is a constant-time lookup;
//   - each agent's last measured distance to the exit it heads for, refreshed time-sliced, and per
//     exit the count of agents heading there by distance (the queue ahead of a given distance),
//     rebuilt 8 times a period and updated by every decision in between;
//   - the groups that choose, as ranges of consecutive ids per population: each group re-evaluated
//     once per period at a tick spread by its id (only the groups due are visited), every group
//     on the tick after an exit closed or opened.
// Herding (social influence): a population's "herding" lowers an exit's cost by the share of the
// people around heading for it (a cell index of who heads where, rebuilt with the queue counts).
// A group's choice is the last entry of a goal list of its own (GoalWriter::giveExitGoals), so
// every reader of goals (GoalView) sees a plain goal. Serial code (spawning, applyCommands): the
// same for any thread or rank count.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "agent_store.hpp"
#include "goals.hpp"
#include "group_table.hpp"
#include "throng/core/parallel.hpp"
#include "throng/nav/distance_field.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

class ExitChoice {
 public:
  /// Distance fields for the exits of populations [firstPopulation, end) not built yet (creation,
  /// crowd insertion). Stairs are priced like route choice (the first such population's factors).
  void prepare(const ScenarioDesc& desc, const nav::NavMesh& mesh, std::uint32_t firstPopulation);
  /// Some population chooses exits.
  [[nodiscard]] bool active() const { return !exits_.empty(); }

  /// A door's polygons closed or opened on the mesh prepare() was given (World: closeDoorFloor):
  /// the open exits' fields are stale until refresh().
  void meshChanged();
  /// Measures on `mesh` from now on (the world's mesh rebuilt with more cut regions): every field
  /// is rebuilt by the next refresh() (a closed exit's when it opens; until then it answers
  /// unreachable, as a closed exit costs anyway).
  void setMesh(const nav::NavMesh& mesh);
  /// Whether refresh() has fields to rebuild.
  [[nodiscard]] bool stale() const { return stale_; }
  /// After meshChanged(): rebuilds the field of every open exit built before the change (a closed
  /// exit's when it opens) on the mesh as it is now — closed doors are walls, an exit behind them
  /// is measured the way round or not at all — one exit per task (each field the same on any
  /// thread count); then every agent heading for an exit re-measures its distance and the queues
  /// are counted anew, and at the next step every group chooses again. Serial callers pass
  /// tasks = nullptr.
  void refresh(const GoalWriter& goals, const core::TaskSystem* tasks);

  /// The exit group `gid` of population `pop` (`members` agents) heads for when it spawns with its
  /// first member at `p` on polygon `ref` (desired speed `speed`); remembers the group for
  /// re-evaluation and counts its members in the exit's queue at once, so the groups spawning
  /// after it in the same tick see them.
  std::uint32_t initial(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t gid, std::uint32_t members,
                        core::Vec2 p, nav::PolyRef ref, float speed);

  /// Closes or opens an exit for choosing (timeline "close" / "open"); closed exits are never
  /// chosen, and a group heading for one chooses again at the next step.
  void setClosed(std::uint32_t point, bool closed);
  [[nodiscard]] bool closed(std::uint32_t point) const;

  /// One tick of choosing: agents due (by id, once a period) measure their distance to the exit
  /// they head for; the queues are counted; groups due (by id), and every group heading for a
  /// closed exit, choose again; a change re-targets the members walking to the exit.
  void step(std::uint64_t tick, std::span<const std::uint32_t> rowOfId, GoalWriter& goals, const core::TaskSystem& tasks);


 private:
  /// Agents heading for one exit by distance bin, as a Fenwick tree: adding one and counting
  /// those nearer than a distance both take O(log bins).
  class Queue {
   public:
    void reset(std::size_t bins) { tree_.assign(bins + 1, 0); }
    void clear() { std::fill(tree_.begin(), tree_.end(), 0); }
    /// `n` more (or fewer) agents at distance `d`.
    void add(float d, std::int32_t n);
    /// Agents strictly nearer than the bin of `d`.
    [[nodiscard]] std::int32_t nearer(float d) const;

   private:
    [[nodiscard]] std::size_t bin(float d) const;
    std::vector<std::int32_t> tree_;
  };
  struct Exit {
    nav::DistanceField field;
    nav::CutRegion region;               ///< where the field measures to (the exit's region)
    nav::DistanceFieldConfig config;     ///< how (stairs priced by the first population naming it)
    std::uint64_t version = 0;           ///< meshVersion_ when the field was built
    float capacity = 1.0f;               ///< persons/s (kExitSpecificFlow × the point's width)
    bool closed = false;
    Queue queue;                         ///< who is heading here, by distance
  };
  /// Groups first .. first + count - 1, all of one population (spawned one after another).
  struct Range {
    std::uint32_t first = 0, count = 0;
    std::uint16_t population = 0;
  };

  /// The cost of exit `e` for a group at distance `d` walking at `speed`: distance (Nearest) or
  /// walking time plus queue time (Quickest); infinite when closed or unreachable.
  [[nodiscard]] double cost(const Exit& e, ExitRule rule, float d, float speed) const;
  /// The group's new exit by `rule` among `pop`'s exits (or `current` when none is better by the
  /// population's hysteresis; kNoPoint as `current`: the best, without hysteresis).
  /// `group`: the deciding group's id (its own members are not "others" for herding; kNoGroup at spawn).
  [[nodiscard]] std::uint32_t better(const PopulationDesc& pop, ExitRule rule, std::uint32_t current, core::Vec2 p,
                                     nav::PolyRef ref, float speed, std::uint32_t group) const;
  /// Herding: per exit of `pop`, the share of the people within the population's herding radius
  /// of p (not of `group`) heading for it, from the last queue count; all 0 when nobody is near.
  void sharesNear(const PopulationDesc& pop, core::Vec2 p, std::uint32_t group, std::vector<double>& share) const;
  [[nodiscard]] Exit& exitAt(std::uint32_t point) { return exits_[static_cast<std::size_t>(exitOfPoint_[point])]; }
  [[nodiscard]] std::uint32_t firstChoice(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t gid, core::Vec2 p,
                                          nav::PolyRef ref, float speed) const;
  /// Every few ticks (or now, with `all`: every agent re-measured) the queues are counted.
  void countQueues(std::uint64_t tick, const GoalWriter& goals, const core::TaskSystem& tasks, bool all = false);
  void reconsider(std::uint64_t tick, std::span<const std::uint32_t> rowOfId, GoalWriter& goals);
  void reconsiderGroup(std::uint32_t gid, const PopulationDesc& pop, std::span<const std::uint32_t> rowOfId, GoalWriter& goals);

  std::vector<Exit> exits_;
  std::vector<std::int32_t> exitOfPoint_;   ///< point index → index into exits_, -1: none
  std::vector<Range> ranges_;               ///< groups that choose, in creation order
  std::vector<float> distanceOfId_;         ///< stable id → last measured distance to its exit [m]
  struct Heading {
    std::uint32_t row = 0, exit = 0;  ///< an agent heading for exits_[exit]
  };
  std::vector<Heading> heading_, measure_;  ///< countQueues' scratch: all, and those re-measured
  /// Herding (when some population uses it): who heads where, by cells of herdCell_ metres, from
  /// the last queue count; cells hashed (x, y) → bucket, each entry (position, exit, group).
  struct Herder {
    float x = 0.0f, y = 0.0f;
    std::uint32_t exit = 0, group = 0;
  };
  std::vector<std::uint32_t> herdStart_;     ///< bucket → first entry in herders_ (size buckets + 1)
  std::vector<Herder> herders_;              ///< sorted by bucket
  float herdCell_ = 0.0f;                    ///< 0: no population herds
  [[nodiscard]] std::uint32_t herdBucket(int cx, int cy) const;
  void indexHerders(const AgentStore& agents);
  std::uint32_t periodTicks_ = 40;          ///< the shortest population period in ticks (distance refresh)
  bool availabilityChanged_ = false;        ///< an exit closed or opened: every group looks again
  const nav::NavMesh* mesh_ = nullptr;      ///< the mesh the fields measure (the world's own copy)
  std::uint64_t meshVersion_ = 0;           ///< doors closed or opened so far (meshChanged)
  bool stale_ = false;                      ///< some open exit's field predates meshVersion_
  bool remeasured_ = false;                 ///< fields rebuilt: every group looks again at the next step
};

}  // namespace throng::sim

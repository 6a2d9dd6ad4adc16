// The spawn phase (spawner.hpp: spawnDue of SpawnInput, SpawnOutput) and the group walking speed:
// the populations due this tick enter the world, in population order. Each is laid out first
// (spawn_layout.hpp: random free spots around group anchors; when they run out in a crowded area,
// the populations sharing it are laid out again on a packed lattice), then its agents get their
// stable ids, rows, speeds, interests, group, first goal and pre-movement wait; speeds (and the
// bodies of the movement-impaired) come from demographics.cpp. Every draw comes from a stream keyed
// by (seed, stable group or agent id, purpose).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "demographics.hpp"
#include "group_pass.hpp"
#include "spawn_layout.hpp"
#include "spawner.hpp"
#include "throng/core/assert.hpp"
#include "throng/core/rng.hpp"

namespace throng::sim {
namespace {

/// The discs of every agent present (new bodies keep clear of them).
SpawnOccupancy occupancyOf(const AgentStore& agents, float cell, std::size_t expected) {
  SpawnOccupancy occupancy(cell, expected);
  for (std::size_t r = 0; r < agents.size(); ++r) {
    occupancy.add({agents.posX[r], agents.posY[r]}, agents.radius[r], agents.levels ? agents.posZ[r] : 0.0f);
  }
  return occupancy;
}

/// Lays out every population due: randomly, then — when random spots ran out in some area — every
/// population whose area overlaps such an area (and so on, transitively) again on the lattice, in
/// population order; the others keep their spots.
class DueLayout {
 public:
  DueLayout(const SpawnInput& in, const SpawnOutput& out, std::span<const std::size_t> due)
      : in_(in), layout_{in.desc, in.query, out.agents.levels}, agents_(out.agents), spawner_(out.spawner), due_(due) {
    std::size_t expected = agents_.size();
    std::uint32_t nextId = spawner_.nextAgentId();
    for (const std::size_t p : due) {
      jobs_.push_back({p, spawner_.groupSizes(p), spawner_.firstGroupId(p), nextId});
      nextId += spawner_.agentsOf(p);
      expected += spawner_.agentsOf(p);
    }
    expected_ = expected;
    cell_ = std::max(0.5f, 4.0f * in.desc.maxRadius());
  }

  std::vector<SpawnPlan> plan() {
    SpawnOccupancy occupancy = occupancyOf(agents_, cell_, expected_);
    std::vector<SpawnPlan> plans;
    plans.reserve(due_.size());
    bool allPlaced = true;
    for (const LayoutJob& job : jobs_) {
      plans.push_back(planRandomSpawn(layout_, job, occupancy));
      allPlaced = allPlaced && plans.back().placed;
    }
    if (!allPlaced) packCrowdedAreas(plans);
    return plans;
  }

 private:
  void packCrowdedAreas(std::vector<SpawnPlan>& plans) const {
    const std::vector<std::uint8_t> redo = crowded(plans);
    SpawnOccupancy occupancy = occupancyOf(agents_, cell_, expected_);
    for (std::size_t k = 0; k < due_.size(); ++k) {
      if (redo[k]) continue;
      const PopulationDesc& pop = in_.desc.populations[due_[k]];
      const float height = spawnArea(in_.desc, pop, 0, agents_.levels).height;
      for (const auto& spot : plans[k].spots) occupancy.add(spot.first, pop.radius, height);
    }
    for (std::size_t k = 0; k < due_.size(); ++k) {
      if (redo[k]) plans[k] = planPackedSpawn(layout_, jobs_[k], occupancy);
    }
  }

  /// Per population due: whether its area is crowded or overlaps a crowded one (transitively).
  [[nodiscard]] std::vector<std::uint8_t> crowded(const std::vector<SpawnPlan>& plans) const {
    std::vector<core::Aabb> boxes;
    std::vector<std::uint8_t> redo(due_.size(), 0);
    for (std::size_t k = 0; k < due_.size(); ++k) {
      const PopulationDesc& pop = in_.desc.populations[due_[k]];
      boxes.push_back(spawnArea(in_.desc, pop, spawner_.agentsOf(due_[k]), agents_.levels).box);
      redo[k] = plans[k].placed ? 0 : 1;
    }
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t k = 0; k < due_.size(); ++k) {
        if (redo[k]) continue;
        for (std::size_t o = 0; o < due_.size() && !redo[k]; ++o) {
          if (redo[o] && boxesOverlap(boxes[k], boxes[o])) redo[k] = grew = true;
        }
      }
    }
    return redo;
  }

  const SpawnInput& in_;
  const LayoutInput layout_;
  const AgentStore& agents_;
  const Spawner& spawner_;
  std::span<const std::size_t> due_;
  std::vector<LayoutJob> jobs_;
  std::size_t expected_ = 0;
  float cell_ = 0.5f;
};

/// Adds the agents of one laid-out population, group by group, in spawn order.
class PopulationEntry {
 public:
  PopulationEntry(const SpawnInput& in, const SpawnOutput& out, const SpawnPlan& plan)
      : in_(in), out_(out), plan_(plan), pop_(in.desc.populations[plan.population]),
        population_(static_cast<std::uint32_t>(plan.population)) {}

  void run() {
    out_.spawner.markSpawned(plan_.population);
    THRONG_ASSERT(out_.spawner.nextAgentId() == plan_.firstAgent);
    const std::span<const std::uint32_t> sizes = out_.spawner.groupSizes(plan_.population);
    std::size_t spot = 0;
    for (std::uint32_t g = 0; g < sizes.size(); ++g) {
      const std::uint32_t groupId = out_.spawner.firstGroupId(plan_.population) + g;
      if (pop_.autoGoals) out_.goals.reconstructGoals(groupId, plan_.anchors[g]);
      const std::uint32_t exit = chooseExit(groupId, sizes[g], plan_.spots[spot]);
      out_.goals.openGoalChoices(groupId);
      for (std::uint32_t m = 0; m < sizes[g]; ++m) {
        const std::size_t row = addRow(groupId, m, sizes[g], plan_.spots[spot++]);
        drawInterests(row);
        joinGroup(row, groupId);
      }
      if (exit != kNoPoint) out_.goals.events.push_back({in_.tick, out_.groups[groupId].leader, EventKind::ExitChosen, exit, kNoPoint});
    }
  }

 private:
  /// Exit choice: the exit the group heads for after its goals, chosen where its first member
  /// stands, in a goal list of its own; kNoPoint when its population names no exits.
  std::uint32_t chooseExit(std::uint32_t groupId, std::uint32_t members, const std::pair<core::Vec2, nav::PolyRef>& first) {
    if (pop_.exits.empty() || out_.exits == nullptr) return kNoPoint;
    const std::uint32_t exit = out_.exits->initial(in_.desc, pop_, groupId, members, first.first, first.second, pop_.speedMean);
    out_.goals.giveExitGoals(groupId, exit);
    return exit;
  }

  /// The agent's row: id, group, body, position, desired speed, standing still facing +x.
  std::size_t addRow(std::uint32_t groupId, std::uint32_t member, std::uint32_t groupSize,
                     const std::pair<core::Vec2, nav::PolyRef>& placed) {
    AgentStore& agents = out_.agents;
    const std::uint32_t agentId = out_.spawner.takeAgentId();
    const std::size_t row = agents.addRow();
    agents.id[row] = agentId;
    agents.group[row] = groupId;
    agents.population[row] = static_cast<std::uint16_t>(population_);
    agents.groupSize[row] = static_cast<std::uint16_t>(std::min<std::uint32_t>(groupSize, 0xffff));
    agents.posX[row] = placed.first.x;
    agents.posY[row] = placed.first.y;
    agents.polyRef[row] = static_cast<std::uint32_t>(placed.second);  // 32-bit Detour references
    if (agents.levels) agents.posZ[row] = placed.second != 0 ? in_.query.heightAt(placed.second, placed.first) : spawnHeight();
    const Walker walker = drawWalker(pop_, in_.desc.seed, agentId);  // demographics.hpp
    agents.radius[row] = walker.impaired ? pop_.demographics.impairedRadius : pop_.radius;
    agents.speed[row] = walker.speed;
    agents.oriX[row] = 1.0f;
    agents.oriY[row] = 0.0f;
    agents.mode[row] = AgentMode::Waiting;
    agents.goalState[row] = GoalState::Seeking;
    agents.goalCursor[row] = 0;
    out_.spawner.recordSpawn(out_.goals.events.size(), in_.tick, population_, agentId, groupId, member);
    ++out_.stats.spawned;
    --out_.stats.scheduled;
    agents.targetSub[row] = -1;
    if (agents.sociological) agents.followAgent[row] = kNoAgent;
    if (agents.commonGround) {
      agents.coordination[row] = kNoIndex;
      agents.desirePoint[row] = kNoPoint;
      agents.scriptClip[row] = kNoClip;
    }
    return row;
  }

  [[nodiscard]] float spawnHeight() const {
    return pop_.spawn.kind == SpawnKind::Point ? in_.desc.points[pop_.spawn.point].height : pop_.spawn.height;
  }

  /// Common Ground: the agent's interests, drawn from its population's without repetition (they
  /// matter only to the goal generator).
  void drawInterests(std::size_t row) {
    AgentStore& agents = out_.agents;
    if (!agents.commonGround || pop_.interests.empty() || pop_.interestsPerAgent == 0) return;
    core::Rng interestRng(in_.desc.seed, agents.id[row], core::RngPurpose::Social);
    std::vector<std::string> pool = pop_.interests;
    for (std::uint32_t k = 0; k < pop_.interestsPerAgent && !pool.empty(); ++k) {
      const std::uint32_t pick = interestRng.uniformInt(0, static_cast<std::uint32_t>(pool.size() - 1));
      const std::int32_t c = in_.commonGround.categoryIndex(pool[pick]);
      if (c >= 0 && c < 64) agents.interests[row] |= std::uint64_t{1} << c;
      pool.erase(pool.begin() + pick);
    }
  }

  /// Joins the group (flocking: everyone walks at the group's speed), heads for its current goal
  /// and faces the first target.
  void joinGroup(std::size_t row, std::uint32_t groupId) {
    AgentStore& agents = out_.agents;
    GroupState& group = out_.groups[groupId];
    group.members.push_back(agents.id[row]);
    if (group.leader == kNoAgent) group.leader = agents.id[row];
    if (group.flocks(pop_)) agents.speed[row] = groupSpeed(in_.desc, out_.groups, groupId);
    out_.goals.setGoal(row, group.cursor);
    const core::Vec2 dir = core::normalize(core::Vec2{agents.targetX[row] - agents.posX[row], agents.targetY[row] - agents.posY[row]});
    if (core::lengthSq(dir) > 0.0f) { agents.oriX[row] = dir.x; agents.oriY[row] = dir.y; }
    agents.progressDistance[row] = 1e30f;
    if (pop_.preMovement.enabled() && agents.goalState[row] == GoalState::Seeking) waitBeforeLeaving(row);
  }

  /// Pre-movement: the agent stands where it appeared until its drawn time is over (decide then
  /// lets it walk); it is an obstacle to the others meanwhile, as anyone standing.
  void waitBeforeLeaving(std::size_t row) {
    AgentStore& agents = out_.agents;
    const double t = preMovementTime(pop_.preMovement, in_.desc.seed, agents.id[row]);
    const double ticks = std::ceil(t / static_cast<double>(in_.desc.dt) - 1e-6);
    const double end = std::min(static_cast<double>(in_.tick) + std::max(ticks, 0.0), 4294967295.0);
    agents.goalState[row] = GoalState::PreMovement;
    agents.mode[row] = AgentMode::Waiting;
    agents.actionEndTick[row] = static_cast<std::uint32_t>(end);
  }

  const SpawnInput& in_;
  const SpawnOutput& out_;
  const SpawnPlan& plan_;
  const PopulationDesc& pop_;
  std::uint32_t population_;
};

}  // namespace

double preMovementTime(const PreMovementDesc& d, std::uint64_t seed, std::uint32_t agentId) {
  core::Rng rng(seed, agentId, core::RngPurpose::PreMovement);
  double t = 0.0;
  switch (d.distribution) {
    case PreMovementDistribution::None: return 0.0;
    case PreMovementDistribution::Uniform: t = rng.uniform(d.min, d.max); break;
    case PreMovementDistribution::Normal: t = rng.normal(d.mean, d.sd); break;
    case PreMovementDistribution::LogNormal: t = std::exp(rng.normal(d.mu, d.sigma)); break;
  }
  return std::clamp(t, 0.0, static_cast<double>(kMaxPreMovement));
}

float groupSpeed(const ScenarioDesc& desc, const GroupTable& groups, std::uint32_t gid) {
  return drawWalker(desc.populations[groups[gid].population], desc.seed, gid).speed;
}

void spawnDue(const SpawnInput& in, const SpawnOutput& out, std::span<const std::size_t> due) {
  if (due.empty()) return;
  const std::vector<SpawnPlan> plans = DueLayout(in, out, due).plan();
  for (const SpawnPlan& plan : plans) PopulationEntry(in, out, plan).run();
  out.stats.active = static_cast<std::uint32_t>(out.agents.size());
}

}  // namespace throng::sim

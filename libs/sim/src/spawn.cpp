// applyCommands — spawning. Holds: the groups of the scenario's populations and of inserted crowds
// (planPopulations, registerGroups: sizes drawn per stable group id), the group walking speed, the
// compact spawn events, and the spawning of the populations due this tick, in population order:
// each is laid out (spawn_layout.cpp: random free spots around group anchors; when they run out
// in a crowded area, the populations sharing it are laid out again on a packed lattice), then its
// agents get their rows, interests, group and first goal; speeds (and the bodies of the
// movement-impaired) come from demographics.cpp. Every draw comes from a stream keyed by
// (seed, stable group or agent id, purpose).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "throng/core/assert.hpp"
#include "throng/core/rng.hpp"
#include "demographics.hpp"
#include "spawn_layout.hpp"
#include "world_impl.hpp"

namespace throng::sim {
void World::Impl::planPopulations() {
  const std::uint32_t scheduled = registerGroups(0);
  // Optional agent columns: only the features some population (or the scenario) uses.
  for (const PopulationDesc& pop : desc.populations) {
    agents.formation = agents.formation || (pop.flocking && pop.sizeMax >= 2);
    agents.sociological = agents.sociological || pop.sociological.enabled;
  }
  agents.commonGround = desc.social.enabled;
  // Every agent that will ever exist is known: exact capacity, no doubling slack on the columns.
  agents.forEachColumn([&](auto& column) { column.reserve(scheduled); });
}

std::uint32_t World::Impl::registerGroups(std::uint32_t firstPopulation) {
  // Group sizes are drawn per stable group id, so a group is the same whether its population came
  // with the scenario or with a crowd.
  THRONG_ASSERT(spawner.groupSizes.size() == firstPopulation && spawner.firstGroupId.size() == firstPopulation);
  const std::uint32_t firstGroup = groups.size();
  std::uint32_t gid = firstGroup, scheduled = 0;
  std::size_t extras = 0;  // cold parts: at most one per busy group (a follower and the group it follows: two)
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const PopulationDesc& pop = desc.populations[p];
    std::vector<std::uint32_t> sizes(pop.groups);
    for (std::uint32_t& size : sizes) {
      core::Rng rng(desc.seed, gid++, core::RngPurpose::GroupSize);
      size = pop.sizeMin == pop.sizeMax ? pop.sizeMin : rng.uniformInt(pop.sizeMin, pop.sizeMax);
      scheduled += size;
      if (desc.social.enabled) ++extras;
      else extras += (pop.follow.mode != FollowMode::None ? 2 : 0) +
                     ((pop.flocking && size >= 2) || !pop.guide.script.empty() || pop.sociological.enabled ? 1 : 0);
    }
    spawner.groupSizes.push_back(std::move(sizes));
  }
  groups.reserve(gid, std::min<std::size_t>(extras, gid));
  // One goal list per population (automatic goals add one per group when it spawns), then its groups.
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const auto goalList = static_cast<std::uint32_t>(goalLists.size());
    goalLists.push_back(desc.populations[p].goals);
    spawner.firstGroupId.push_back(groups.size());
    for (const std::uint32_t size : spawner.groupSizes[p]) {
      GroupState state;
      state.population = static_cast<std::uint16_t>(p);
      state.expected = size;
      state.goalList = goalList;
      groups.add(std::move(state));
    }
  }
  stats.scheduled += scheduled;
  // Busy groups, routes and cold parts.
  for (std::uint32_t gid = firstGroup; gid < groups.size(); ++gid) {
    const PopulationDesc& pop = desc.populations[groups[gid].population];
    const FollowDesc& f = pop.follow;
    if (f.mode != FollowMode::None && f.population < spawner.firstGroupId.size() && f.group < desc.populations[f.population].groups) {
      const std::uint32_t followed = spawner.firstGroupId[f.population] + f.group;
      groups.markBusy(followed);
      groups.routeFor(gid).followGroup = followed;
    }
    if (!pop.guide.script.empty()) groups.routeFor(gid);
    if ((pop.flocking && groups[gid].expected >= 2) || pop.sociological.enabled) groups.markBusy(gid);
    // Common Ground may start a coordination in any group (a lone visit too).
    if (desc.social.enabled) groups.giveExtra(gid);
  }
  return scheduled;
}

float groupSpeed(const ScenarioDesc& desc, const GroupTable& groups, std::uint32_t gid) {
  return drawWalker(desc.populations[groups[gid].population], desc.seed, gid).speed;
}

void World::Impl::recordSpawn(std::uint32_t population, std::uint32_t agent, std::uint32_t group, std::uint32_t member) {
  if (!spawnRuns.empty()) {
    SpawnRun& run = spawnRuns.back();
    // The same run goes on while nothing else happened in between.
    if (run.at == pendingEvents.size() && run.tick == tick && run.population == population && run.firstAgent + run.count == agent) {
      ++run.count;
      return;
    }
  }
  spawnRuns.push_back({pendingEvents.size(), tick, population, agent, 1, group, member});
}

std::vector<Event> World::Impl::takeEvents() {
  if (spawnRuns.empty()) return std::move(pendingEvents);
  std::size_t total = pendingEvents.size();
  for (const SpawnRun& run : spawnRuns) total += run.count;
  std::vector<Event> out;
  out.reserve(total);
  std::size_t next = 0;
  for (const SpawnRun& run : spawnRuns) {
    out.insert(out.end(), pendingEvents.begin() + static_cast<std::ptrdiff_t>(next), pendingEvents.begin() + static_cast<std::ptrdiff_t>(run.at));
    next = run.at;
    // Walk the population's groups from the run's first agent (groups in id order, members in
    // spawn order; empty groups spawn nobody).
    const std::vector<std::uint32_t>& sizes = spawner.groupSizes[run.population];
    std::uint32_t group = run.group, member = run.member;
    for (std::uint32_t i = 0; i < run.count; ++i) {
      while (member >= sizes[group - spawner.firstGroupId[run.population]]) {
        ++group;
        member = 0;
      }
      out.push_back({run.tick, run.firstAgent + i, EventKind::Spawn, run.population, group});
      ++member;
    }
  }
  out.insert(out.end(), pendingEvents.begin() + static_cast<std::ptrdiff_t>(next), pendingEvents.end());
  spawnRuns.clear();
  std::vector<Event>().swap(pendingEvents);  // as if moved out
  return out;
}

void World::Impl::applyCommands() {
  applyCrowdCommands();  // inserted crowds' populations starting now spawn below
  std::vector<std::size_t> due;
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    if (!spawner.spawned[p] && spawner.startTick[p] <= tick) due.push_back(p);
  }
  if (!due.empty()) spawnPopulations(due);
}


void World::Impl::spawnPopulations(const std::vector<std::size_t>& due) {
  std::size_t expected = agents.size();
  std::vector<std::uint32_t> firstAgent;
  std::uint32_t nextId = spawner.nextAgentId;
  for (const std::size_t p : due) {
    firstAgent.push_back(nextId);
    for (const std::uint32_t s : spawner.groupSizes[p]) nextId += s;
    expected += nextId - firstAgent.back();
  }
  const float cell = std::max(0.5f, 4.0f * desc.maxRadius());
  auto occupied = [&] {
    SpawnOccupancy occupancy(cell, expected);
    for (std::size_t r = 0; r < agents.size(); ++r) {
      occupancy.add({agents.posX[r], agents.posY[r]}, agents.radius[r], agents.levels ? agents.posZ[r] : 0.0f);
    }
    return occupancy;
  };
  SpawnOccupancy occupancy = occupied();
  std::vector<SpawnPlan> plans;
  plans.reserve(due.size());
  bool allPlaced = true;
  for (std::size_t k = 0; k < due.size(); ++k) {
    plans.push_back(planRandomSpawn(due[k], firstAgent[k], occupancy));
    allPlaced = allPlaced && plans.back().placed;
  }
  if (!allPlaced) {
    // Random spots ran out in some area. Every population whose area overlaps such an area (and
    // so on, transitively) is laid out again on the lattice, in population order; the others keep
    // their spots.
    std::vector<core::Aabb> boxes;
    std::vector<std::uint8_t> redo(due.size(), 0);
    for (std::size_t k = 0; k < due.size(); ++k) {
      std::uint32_t total = 0;
      for (const std::uint32_t s : spawner.groupSizes[due[k]]) total += s;
      boxes.push_back(spawnArea(desc, desc.populations[due[k]], total, agents.levels).box);
      redo[k] = plans[k].placed ? 0 : 1;
    }
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t k = 0; k < due.size(); ++k) {
        if (redo[k]) continue;
        for (std::size_t o = 0; o < due.size() && !redo[k]; ++o) {
          if (redo[o] && boxesOverlap(boxes[k], boxes[o])) redo[k] = grew = true;
        }
      }
    }
    occupancy = occupied();
    for (std::size_t k = 0; k < due.size(); ++k) {
      if (redo[k]) continue;
      const PopulationDesc& pop = desc.populations[due[k]];
      const float height = spawnArea(desc, pop, 0, agents.levels).height;
      for (const auto& spot : plans[k].spots) occupancy.add(spot.first, pop.radius, height);
    }
    for (std::size_t k = 0; k < due.size(); ++k) {
      if (redo[k]) plans[k] = planPackedSpawn(due[k], firstAgent[k], occupancy);
    }
  }
  for (const SpawnPlan& plan : plans) addSpawnedAgents(plan);
  stats.active = static_cast<std::uint32_t>(agents.size());
  rowsChanged = true;
}

void World::Impl::addSpawnedAgents(const SpawnPlan& plan) {
  const std::size_t populationIndex = plan.population;
  const PopulationDesc& pop = desc.populations[populationIndex];
  spawner.spawned[populationIndex] = 1;
  const nav::NavQuery& query = *mainQuery;
  GoalWriter goals = goalWriter();
  const std::vector<std::uint32_t>& sizes = spawner.groupSizes[populationIndex];
  const float spawnHeight = pop.spawn.kind == SpawnKind::Point ? desc.points[pop.spawn.point].height : pop.spawn.height;
  THRONG_ASSERT(spawner.nextAgentId == plan.firstAgent);
  std::size_t spot = 0;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    const std::uint32_t groupId = spawner.firstGroupId[populationIndex] + g;
    if (pop.autoGoals) goals.reconstructGoals(groupId, plan.anchors[g]);
    for (std::uint32_t m = 0; m < sizes[g]; ++m) {
      const std::uint32_t agentId = spawner.nextAgentId++;
      const std::pair<core::Vec2, nav::PolyRef>* placed = &plan.spots[spot++];
      const std::size_t row = agents.addRow();
      agents.id[row] = agentId;
      agents.group[row] = groupId;
      agents.population[row] = static_cast<std::uint16_t>(populationIndex);
      agents.groupSize[row] = static_cast<std::uint16_t>(std::min<std::uint32_t>(sizes[g], 0xffff));
      agents.posX[row] = placed->first.x;
      agents.posY[row] = placed->first.y;
      agents.polyRef[row] = static_cast<std::uint32_t>(placed->second);  // 32-bit Detour references
      if (agents.levels) agents.posZ[row] = placed->second != 0 ? query.heightAt(placed->second, placed->first) : spawnHeight;
      const Walker walker = drawWalker(pop, desc.seed, agentId);  // demographics.hpp
      agents.radius[row] = walker.impaired ? pop.demographics.impairedRadius : pop.radius;
      agents.speed[row] = walker.speed;
      agents.oriX[row] = 1.0f;
      agents.oriY[row] = 0.0f;
      agents.mode[row] = AgentMode::Waiting;
      agents.goalState[row] = GoalState::Seeking;
      agents.goalCursor[row] = 0;
      recordSpawn(static_cast<std::uint32_t>(populationIndex), agentId, groupId, m);
      ++stats.spawned;
      --stats.scheduled;
      agents.targetSub[row] = -1;
      if (agents.sociological) agents.followAgent[row] = kNoAgent;
      if (agents.commonGround) {
        agents.coordination[row] = kNoIndex;
        agents.desirePoint[row] = kNoPoint;
        agents.scriptClip[row] = kNoClip;
      }
      // Interests matter only to the goal generator (Common Ground on).
      if (agents.commonGround && !pop.interests.empty() && pop.interestsPerAgent > 0) {
        // Common Ground: this agent's interests, drawn from its population's without repetition.
        core::Rng interestRng(desc.seed, agentId, core::RngPurpose::Social);
        std::vector<std::string> pool = pop.interests;
        for (std::uint32_t k = 0; k < pop.interestsPerAgent && !pool.empty(); ++k) {
          const std::uint32_t pick = interestRng.uniformInt(0, static_cast<std::uint32_t>(pool.size() - 1));
          const std::int32_t c = commonGround.categoryIndex(pool[pick]);
          if (c >= 0 && c < 64) agents.interests[row] |= std::uint64_t{1} << c;
          pool.erase(pool.begin() + pick);
        }
      }
      // Join the group (flocking: everyone walks at the group's speed) and head for its current goal.
      GroupState& group = groups[groupId];
      group.members.push_back(agentId);
      if (group.leader == kNoAgent) group.leader = agentId;
      if (group.flocks(pop)) agents.speed[row] = groupSpeed(desc, groups, groupId);
      goals.setGoal(row, group.cursor);
      // Face the first target.
      const core::Vec2 dir = core::normalize(core::Vec2{agents.targetX[row] - agents.posX[row], agents.targetY[row] - agents.posY[row]});
      if (core::lengthSq(dir) > 0.0f) { agents.oriX[row] = dir.x; agents.oriY[row] = dir.y; }
      agents.progressDistance[row] = 1e30f;
    }
  }
}

}  // namespace throng::sim

// Spawner (spawner.hpp) — the schedule of populations, their groups (registerGroups: sizes drawn
// per stable group id, so a group is the same whether its population came with the scenario or
// with a crowd), the stable agent ids, and the spawn events kept compactly until a frame takes
// them.
#include "spawner.hpp"

#include <algorithm>
#include <numeric>

#include "throng/core/assert.hpp"
#include "throng/core/rng.hpp"

namespace throng::sim {

void Spawner::addPopulation(std::uint64_t startTick) {
  startTick_.push_back(startTick);
  spawned_.push_back(0);
}

std::vector<std::size_t> Spawner::due(std::uint64_t tick) const {
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < startTick_.size(); ++p) {
    if (!spawned_[p] && startTick_[p] <= tick) out.push_back(p);
  }
  return out;
}

bool Spawner::allSpawned() const {
  return std::all_of(spawned_.begin(), spawned_.end(), [](std::uint8_t s) { return s != 0; });
}

std::uint32_t Spawner::cancel(std::size_t population) {
  if (spawned_[population]) return 0;
  spawned_[population] = 1;
  return agentsOf(population);
}

std::uint32_t Spawner::agentsOf(std::size_t population) const {
  const std::vector<std::uint32_t>& sizes = groupSizes_[population];
  return std::accumulate(sizes.begin(), sizes.end(), 0u);
}

std::uint32_t Spawner::registerGroups(const ScenarioDesc& desc, std::uint32_t firstPopulation, GroupTable& groups,
                                      std::vector<std::vector<std::uint32_t>>& goalLists) {
  THRONG_ASSERT(groupSizes_.size() == firstPopulation && firstGroupId_.size() == firstPopulation);
  THRONG_ASSERT(startTick_.size() == desc.populations.size());
  const std::uint32_t firstGroup = groups.size();
  const DrawnSizes drawn = drawGroupSizes(desc, firstPopulation, firstGroup);
  groups.reserve(drawn.groupEnd, std::min<std::size_t>(drawn.extras, drawn.groupEnd));
  addGroups(desc, firstPopulation, groups, goalLists);
  markBusyAndRoutes(desc, firstGroup, groups);
  return drawn.scheduled;
}

Spawner::DrawnSizes Spawner::drawGroupSizes(const ScenarioDesc& desc, std::uint32_t firstPopulation,
                                            std::uint32_t firstGroup) {
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
    groupSizes_.push_back(std::move(sizes));
  }
  return {scheduled, gid, extras};
}

void Spawner::addGroups(const ScenarioDesc& desc, std::uint32_t firstPopulation, GroupTable& groups,
                        std::vector<std::vector<std::uint32_t>>& goalLists) {
  // One goal list per population (automatic goals add one per group when it spawns), then its groups.
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const auto goalList = static_cast<std::uint32_t>(goalLists.size());
    goalLists.push_back(desc.populations[p].goals);
    firstGroupId_.push_back(groups.size());
    for (const std::uint32_t size : groupSizes_[p]) {
      GroupState state;
      state.population = static_cast<std::uint16_t>(p);
      state.expected = size;
      state.goalList = goalList;
      groups.add(std::move(state));
    }
  }
}

void Spawner::markBusyAndRoutes(const ScenarioDesc& desc, std::uint32_t firstGroup, GroupTable& groups) const {
  for (std::uint32_t gid = firstGroup; gid < groups.size(); ++gid) {
    const PopulationDesc& pop = desc.populations[groups[gid].population];
    const FollowDesc& f = pop.follow;
    if (f.mode != FollowMode::None && f.population < firstGroupId_.size() && f.group < desc.populations[f.population].groups) {
      const std::uint32_t followed = firstGroupId_[f.population] + f.group;
      groups.markBusy(followed);
      groups.routeFor(gid).followGroup = followed;
    }
    if (!pop.guide.script.empty()) groups.routeFor(gid);
    if ((pop.flocking && groups[gid].expected >= 2) || pop.sociological.enabled) groups.markBusy(gid);
    // Common Ground may start a coordination in any group (a lone visit too).
    if (desc.social.enabled) groups.giveExtra(gid);
  }
}

void Spawner::recordSpawn(std::size_t at, std::uint64_t tick, std::uint32_t population, std::uint32_t agent,
                          std::uint32_t group, std::uint32_t member) {
  if (!runs_.empty()) {
    SpawnRun& run = runs_.back();
    // The same run goes on while nothing else happened in between.
    if (run.at == at && run.tick == tick && run.population == population && run.firstAgent + run.count == agent) {
      ++run.count;
      return;
    }
  }
  runs_.push_back({at, tick, population, agent, 1, group, member});
}

std::vector<Event> Spawner::takeEvents(std::vector<Event>& pending) {
  if (runs_.empty()) {
    std::vector<Event> out = std::move(pending);
    pending.clear();
    return out;
  }
  std::size_t total = pending.size();
  for (const SpawnRun& run : runs_) total += run.count;
  std::vector<Event> out;
  out.reserve(total);
  std::size_t next = 0;
  for (const SpawnRun& run : runs_) {
    out.insert(out.end(), pending.begin() + static_cast<std::ptrdiff_t>(next), pending.begin() + static_cast<std::ptrdiff_t>(run.at));
    next = run.at;
    expand(run, out);
  }
  out.insert(out.end(), pending.begin() + static_cast<std::ptrdiff_t>(next), pending.end());
  runs_.clear();
  std::vector<Event>().swap(pending);  // as if moved out
  return out;
}

void Spawner::expand(const SpawnRun& run, std::vector<Event>& out) const {
  // Walk the population's groups from the run's first agent (groups in id order, members in spawn
  // order; empty groups spawn nobody).
  const std::vector<std::uint32_t>& sizes = groupSizes_[run.population];
  std::uint32_t group = run.group, member = run.member;
  for (std::uint32_t i = 0; i < run.count; ++i) {
    while (member >= sizes[group - firstGroupId_[run.population]]) {
      ++group;
      member = 0;
    }
    out.push_back({run.tick, run.firstAgent + i, EventKind::Spawn, run.population, group});
    ++member;
  }
}

}  // namespace throng::sim

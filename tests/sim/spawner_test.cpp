// Tests for libs/sim/src/spawner.hpp: the Spawner's schedule, registerGroups (creation and run-time
// insertion alike), the compact spawn events, and the spawn phase (spawnDue) called on its own
// through its context on hand-built state (no World; tests/sim/goal_world.hpp).
#include "spawner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <set>
#include <vector>

#include "goal_world.hpp"

using namespace throng;
using namespace throng::sim;

using test::GoalWorld;
using test::rect;

namespace {

/// A population of `groups` groups of `sizeMin`..`sizeMax` members heading for point 0.
PopulationDesc population(std::uint32_t groups, std::uint32_t sizeMin, std::uint32_t sizeMax) {
  PopulationDesc pop;
  pop.groups = groups;
  pop.sizeMin = sizeMin;
  pop.sizeMax = sizeMax;
  pop.goals = {0};
  return pop;
}

/// What registerGroups leaves behind, comparable.
struct Registered {
  std::vector<std::vector<std::uint32_t>> sizes;
  std::vector<std::uint32_t> firstGroup;
  std::vector<std::vector<std::uint32_t>> goalLists;
  std::vector<std::uint32_t> busy;
  std::vector<std::uint32_t> followed;  ///< per group: the group its route follows
  std::uint32_t scheduled = 0;
  bool operator==(const Registered&) const = default;
};

Registered snapshot(const Spawner& s, GroupTable& groups, const std::vector<std::vector<std::uint32_t>>& goalLists,
                    std::uint32_t scheduled) {
  Registered r;
  for (std::size_t p = 0; p < s.populations(); ++p) {
    r.sizes.emplace_back(s.groupSizes(p).begin(), s.groupSizes(p).end());
    r.firstGroup.push_back(s.firstGroupId(p));
  }
  r.goalLists = goalLists;
  groups.refreshBusy();
  r.busy = groups.busy();
  for (const GroupState& g : groups) r.followed.push_back(groups.routeOf(g).followGroup);
  r.scheduled = scheduled;
  return r;
}

}  // namespace

TEST(Spawner, ScheduleHandsOutDuePopulationsOnceInOrder) {
  Spawner s;
  s.addPopulation(0);
  s.addPopulation(10);
  s.addPopulation(5);
  EXPECT_EQ(s.populations(), 3u);
  EXPECT_EQ(s.due(0), (std::vector<std::size_t>{0}));
  EXPECT_EQ(s.due(7), (std::vector<std::size_t>{0, 2}));
  s.markSpawned(0);
  EXPECT_TRUE(s.spawned(0));
  EXPECT_EQ(s.due(7), (std::vector<std::size_t>{2})) << "a population spawns once";
  EXPECT_FALSE(s.allSpawned());
  s.markSpawned(2);
  EXPECT_EQ(s.due(20), (std::vector<std::size_t>{1}));
  s.markSpawned(1);
  EXPECT_TRUE(s.allSpawned());
  EXPECT_TRUE(s.due(100).empty());
}

TEST(Spawner, RegisterGroupsDrawsSizesPerStableGroupIdSoInsertionMatchesCreation) {
  // Two populations with drawn sizes (1..4) and a third that follows group 1 of the first:
  // registered all at once (creation) and one by one (each an inserted crowd), the sizes, ids,
  // goal lists, busy set and routes are the same.
  ScenarioDesc desc;
  desc.seed = 42;
  desc.populations = {population(5, 1, 4), population(3, 1, 4), population(2, 2, 2)};
  desc.populations[1].flocking = true;
  desc.populations[2].follow.mode = FollowMode::Permanent;
  desc.populations[2].follow.population = 0;
  desc.populations[2].follow.group = 1;
  desc.populations[2].goals = {1, 0};

  Spawner all;
  GroupTable allGroups;
  std::vector<std::vector<std::uint32_t>> allLists;
  for (std::size_t p = 0; p < 3; ++p) all.addPopulation(0);
  const std::uint32_t allScheduled = all.registerGroups(desc, 0, allGroups, allLists);

  Spawner one;
  GroupTable oneGroups;
  std::vector<std::vector<std::uint32_t>> oneLists;
  ScenarioDesc growing = desc;
  growing.populations.clear();
  std::uint32_t oneScheduled = 0;
  for (std::uint32_t p = 0; p < 3; ++p) {
    growing.populations.push_back(desc.populations[p]);
    one.addPopulation(0);
    oneScheduled += one.registerGroups(growing, p, oneGroups, oneLists);
  }
  const Registered a = snapshot(all, allGroups, allLists, allScheduled);
  const Registered b = snapshot(one, oneGroups, oneLists, oneScheduled);
  EXPECT_EQ(a, b);

  // And what was registered is what the populations asked for.
  EXPECT_EQ(a.firstGroup, (std::vector<std::uint32_t>{0, 5, 8}));
  EXPECT_EQ(a.goalLists, (std::vector<std::vector<std::uint32_t>>{{0}, {0}, {1, 0}}));
  std::set<std::uint32_t> drawn;
  std::uint32_t total = 0;
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_EQ(all.agentsOf(p), [&] { std::uint32_t n = 0; for (auto s : a.sizes[p]) n += s; return n; }());
    total += all.agentsOf(p);
    for (const std::uint32_t s : a.sizes[p]) {
      EXPECT_GE(s, desc.populations[p].sizeMin);
      EXPECT_LE(s, desc.populations[p].sizeMax);
      drawn.insert(s);
    }
  }
  EXPECT_GT(drawn.size(), 1u) << "sizes are drawn, not all the same";
  EXPECT_EQ(a.scheduled, total);
  ASSERT_EQ(allGroups.size(), 10u);
  for (std::uint32_t g = 0; g < 10; ++g) {
    const std::size_t p = g < 5 ? 0 : g < 8 ? 1 : 2;
    EXPECT_EQ(allGroups[g].population, p);
    EXPECT_EQ(allGroups[g].expected, a.sizes[p][g - a.firstGroup[p]]);
    EXPECT_EQ(allGroups[g].goalList, p);
  }
  // The followers (groups 8, 9) follow group 1, which is busy; flocking groups of 2+ are busy.
  EXPECT_EQ(a.followed[8], 1u);
  EXPECT_EQ(a.followed[9], 1u);
  EXPECT_TRUE(std::binary_search(a.busy.begin(), a.busy.end(), 1u));
  for (std::uint32_t g = 5; g < 8; ++g) {
    EXPECT_EQ(std::binary_search(a.busy.begin(), a.busy.end(), g), allGroups[g].expected >= 2) << "group " << g;
  }
}

TEST(Spawner, CancelledPopulationGivesBackWhatItWouldHaveSpawned) {
  ScenarioDesc desc;
  desc.populations = {population(3, 2, 2), population(1, 4, 4)};
  Spawner s;
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> lists;
  s.addPopulation(0);
  s.addPopulation(50);
  EXPECT_EQ(s.registerGroups(desc, 0, groups, lists), 10u);
  s.markSpawned(0);
  EXPECT_EQ(s.cancel(0), 0u) << "already spawned: nothing left to spawn";
  EXPECT_EQ(s.cancel(1), 4u);
  EXPECT_EQ(s.cancel(1), 0u);
  EXPECT_TRUE(s.allSpawned());
  EXPECT_TRUE(s.due(100).empty());
}

TEST(Spawner, SpawnEventsAreWrittenOutInPlace) {
  // Population 1's groups 3 and 4 hold two agents each (0, 1 | 2, 3); a GoalReached event
  // happened between agent 1's and agent 2's spawn, another one before.
  ScenarioDesc desc;
  desc.populations = {population(3, 1, 1), population(2, 2, 2)};
  Spawner s;
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> lists;
  s.addPopulation(0);
  s.addPopulation(0);
  s.registerGroups(desc, 0, groups, lists);
  std::vector<Event> pending;
  pending.push_back({3, 99, EventKind::GoalReached, 0, 0});
  for (std::uint32_t m = 0; m < 2; ++m) s.recordSpawn(pending.size(), 4, 1, s.takeAgentId(), 3, m);
  pending.push_back({4, 98, EventKind::GoalReached, 1, 0});
  s.recordSpawn(pending.size(), 4, 1, s.takeAgentId(), 4, 0);
  s.recordSpawn(pending.size(), 4, 1, s.takeAgentId(), 4, 1);
  const std::vector<Event> out = s.takeEvents(pending);
  EXPECT_TRUE(pending.empty());
  ASSERT_EQ(out.size(), 6u);
  EXPECT_EQ(out[0].agent, 99u);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> spawned{{0, 3}, {1, 3}};
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(out[1 + i].kind, EventKind::Spawn);
    EXPECT_EQ(out[1 + i].agent, spawned[i].first);
    EXPECT_EQ(out[1 + i].a, 1u) << "population";
    EXPECT_EQ(out[1 + i].b, spawned[i].second) << "group";
    EXPECT_EQ(out[1 + i].tick, 4u);
  }
  EXPECT_EQ(out[3].agent, 98u);
  EXPECT_EQ(out[4].agent, 2u);
  EXPECT_EQ(out[4].b, 4u);
  EXPECT_EQ(out[5].agent, 3u);
  EXPECT_EQ(out[5].b, 4u);
  EXPECT_TRUE(s.takeEvents(pending).empty()) << "taken once";
}

TEST(Spawner, SpawnEventsOfOneRunNameEachAgentsGroupPastEmptyGroups) {
  // Sizes 0..2 drawn per group: agents spawned one after another with nothing in between are kept
  // as one run, yet each agent's event names its own group, empty groups taking nobody.
  ScenarioDesc desc;
  desc.seed = 3;
  desc.populations = {population(40, 0, 2)};
  Spawner s;
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> lists;
  s.addPopulation(0);
  const std::uint32_t n = s.registerGroups(desc, 0, groups, lists);
  const auto sizes = s.groupSizes(0);
  ASSERT_TRUE(std::count(sizes.begin(), sizes.end(), 0u) > 0) << "some group is empty (seed 3)";
  std::vector<std::uint32_t> expectedGroup;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) expectedGroup.insert(expectedGroup.end(), sizes[g], g);
  ASSERT_EQ(expectedGroup.size(), n);
  std::vector<Event> pending;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    for (std::uint32_t m = 0; m < sizes[g]; ++m) s.recordSpawn(0, 0, 0, s.takeAgentId(), g, m);
  }
  const std::vector<Event> out = s.takeEvents(pending);
  ASSERT_EQ(out.size(), n);
  for (std::uint32_t i = 0; i < n; ++i) {
    EXPECT_EQ(out[i].agent, i);
    EXPECT_EQ(out[i].b, expectedGroup[i]) << "agent " << i;
  }
}

namespace {

/// GoalWorld (20 × 10 m room, points at x = 5 and 15) with no agents, and `pops` to spawn in a
/// 4 × 4 m square around (10, 5).
struct SpawnWorld {
  GoalWorld w{0};
  Spawner spawner;
  WorldStats stats;
  CommonGroundState commonGround;

  explicit SpawnWorld(std::vector<PopulationDesc> pops) {
    w.desc.seed = 11;
    w.desc.populations = std::move(pops);
    w.groups = GroupTable{};
    w.goalLists.clear();
    for (PopulationDesc& pop : w.desc.populations) {
      pop.spawn.kind = SpawnKind::Polygon;
      pop.spawn.polygon = rect(8, 3, 12, 7);
      spawner.addPopulation(0);
    }
    stats.scheduled = spawner.registerGroups(w.desc, 0, w.groups, w.goalLists);
  }
  void spawn(std::uint64_t tick) {
    GoalWriter goals = w.writer();
    spawnDue(SpawnInput{w.desc, *w.query, tick, commonGround}, SpawnOutput{spawner, w.agents, w.groups, goals, stats},
             spawner.due(tick));
  }
};

}  // namespace

TEST(Spawner, SpawnDuePlacesEachAgentInItsAreaJoinsItsGroupAndHeadsForItsGoal) {
  PopulationDesc walkers = population(4, 1, 3);
  walkers.speedMean = 1.3f;
  walkers.speedSd = 0.2f;
  walkers.speedMin = 0.5f;
  walkers.speedMax = 2.0f;
  SpawnWorld s({walkers});
  const std::uint32_t total = s.spawner.agentsOf(0);
  s.spawn(0);
  const AgentStore& a = s.w.agents;
  ASSERT_EQ(a.size(), total);
  EXPECT_EQ(s.stats.spawned, total);
  EXPECT_EQ(s.stats.scheduled, 0u);
  EXPECT_EQ(s.stats.active, total);
  EXPECT_TRUE(s.spawner.spawned(0));
  EXPECT_EQ(s.spawner.nextAgentId(), total);
  std::set<float> speeds;
  for (std::size_t r = 0; r < a.size(); ++r) {
    EXPECT_EQ(a.id[r], r) << "stable ids in spawn order";
    EXPECT_GE(a.posX[r], 8.0f);
    EXPECT_LE(a.posX[r], 12.0f);
    EXPECT_GE(a.posY[r], 3.0f);
    EXPECT_LE(a.posY[r], 7.0f);
    EXPECT_GE(a.speed[r], 0.5f);
    EXPECT_LE(a.speed[r], 2.0f);
    speeds.insert(a.speed[r]);
    EXPECT_EQ(a.goalState[r], GoalState::Seeking);
    EXPECT_NEAR(a.targetX[r], 5.0f, 3.0f) << "heading for point 0";
    EXPECT_LT(a.oriX[r], 0.0f) << "facing west, toward its target";
    const GroupState& g = s.w.groups[a.group[r]];
    EXPECT_NE(std::find(g.members.begin(), g.members.end(), a.id[r]), g.members.end());
    for (std::size_t o = r + 1; o < a.size(); ++o) {
      EXPECT_GE(core::length(core::Vec2{a.posX[r] - a.posX[o], a.posY[r] - a.posY[o]}), 2 * walkers.radius);
    }
  }
  EXPECT_GT(speeds.size(), 1u) << "speeds drawn per agent";
  for (std::uint32_t g = 0; g < s.w.groups.size(); ++g) {
    EXPECT_EQ(s.w.groups[g].members.size(), s.spawner.groupSizes(0)[g]);
    if (!s.w.groups[g].members.empty()) EXPECT_EQ(s.w.groups[g].leader, s.w.groups[g].members.front());
  }
  // One spawn event per agent, in order, naming population and group.
  std::vector<Event> pending = std::move(s.w.events);
  const std::vector<Event> events = s.spawner.takeEvents(pending);
  ASSERT_EQ(events.size(), total);
  for (std::size_t r = 0; r < a.size(); ++r) {
    EXPECT_EQ(events[r].kind, EventKind::Spawn);
    EXPECT_EQ(events[r].agent, a.id[r]);
    EXPECT_EQ(events[r].b, a.group[r]);
  }
}

TEST(Spawner, SpawnDueLeavesLaterPopulationsAndIsTheSameTwice) {
  // The second population starts later: only the first spawns now. Two worlds spawned alike are
  // identical (every draw comes from (seed, stable id)).
  auto positions = [] {
    SpawnWorld s({population(3, 2, 2), population(2, 1, 1)});
    s.spawner = Spawner{};
    s.w.groups = GroupTable{};
    s.w.goalLists.clear();
    s.spawner.addPopulation(0);
    s.spawner.addPopulation(20);
    s.stats.scheduled = s.spawner.registerGroups(s.w.desc, 0, s.w.groups, s.w.goalLists);
    s.spawn(0);
    EXPECT_EQ(s.w.agents.size(), 6u);
    EXPECT_EQ(s.stats.scheduled, 2u);
    EXPECT_FALSE(s.spawner.spawned(1));
    s.spawn(20);
    EXPECT_EQ(s.w.agents.size(), 8u);
    EXPECT_EQ(s.w.agents.population[7], 1u);
    EXPECT_EQ(s.w.agents.group[7], 4u);
    std::vector<float> out(s.w.agents.posX.begin(), s.w.agents.posX.end());
    out.insert(out.end(), s.w.agents.posY.begin(), s.w.agents.posY.end());
    return out;
  };
  EXPECT_EQ(positions(), positions());
}

TEST(Spawner, SpawnDueHoldsACrowdedAreaWithoutOverlap) {
  // 75 agents of r = 0.2 m in 16 m² (59 % covered, beyond what random placement reaches): the
  // packed lattice holds them.
  PopulationDesc crowd = population(75, 1, 1);
  crowd.radius = 0.2f;
  SpawnWorld s({crowd});
  s.spawn(0);
  const AgentStore& a = s.w.agents;
  ASSERT_EQ(a.size(), 75u);
  for (std::size_t r = 0; r < a.size(); ++r) {
    EXPECT_GE(a.posX[r], 8.0f - 0.02f);
    EXPECT_LE(a.posX[r], 12.0f + 0.02f);
    EXPECT_GE(a.posY[r], 3.0f - 0.02f);
    EXPECT_LE(a.posY[r], 7.0f + 0.02f);
    for (std::size_t o = r + 1; o < a.size(); ++o) {
      EXPECT_GE(core::length(core::Vec2{a.posX[r] - a.posX[o], a.posY[r] - a.posY[o]}), 0.4f - 1e-4f)
          << "agents " << r << " and " << o;
    }
  }
}

TEST(Spawner, PreMovementTimesFollowTheirDistributionPerStableId) {
  // 2000 agents: uniform 10-100 s stays inside and averages 55 s; a normal around 5 s with sd 10 s
  // is clamped at 0; a log-normal has median e^mu. Each draw depends on (seed, id) only.
  PreMovementDesc uniform;
  uniform.distribution = PreMovementDistribution::Uniform;
  uniform.min = 10.0f;
  uniform.max = 100.0f;
  PreMovementDesc normal;
  normal.distribution = PreMovementDistribution::Normal;
  normal.mean = 5.0f;
  normal.sd = 10.0f;
  PreMovementDesc lognormal;
  lognormal.distribution = PreMovementDistribution::LogNormal;
  lognormal.mu = static_cast<float>(std::log(30.0));
  lognormal.sigma = 0.5f;
  constexpr std::uint32_t kAgents = 2000;
  double sum = 0.0;
  std::uint32_t zeros = 0;
  std::vector<double> logs;
  for (std::uint32_t id = 0; id < kAgents; ++id) {
    const double u = preMovementTime(uniform, 7, id);
    EXPECT_GE(u, 10.0);
    EXPECT_LE(u, 100.0);
    EXPECT_EQ(u, preMovementTime(uniform, 7, id)) << "the same draw every time";
    sum += u;
    const double n = preMovementTime(normal, 7, id);
    EXPECT_GE(n, 0.0) << "normal draws are clamped at 0";
    zeros += n == 0.0 ? 1 : 0;
    logs.push_back(preMovementTime(lognormal, 7, id));
    EXPECT_GT(logs.back(), 0.0);
  }
  EXPECT_NEAR(sum / kAgents, 55.0, 2.0);
  EXPECT_GT(zeros, kAgents / 5) << "about 31 % of N(5, 10) is negative";
  std::sort(logs.begin(), logs.end());
  EXPECT_NEAR(logs[kAgents / 2], 30.0, 2.0) << "median e^mu";
  EXPECT_NE(preMovementTime(uniform, 7, 0), preMovementTime(uniform, 8, 0)) << "the seed matters";
  EXPECT_NE(preMovementTime(uniform, 7, 0), preMovementTime(uniform, 7, 1)) << "each agent draws its own";
  EXPECT_EQ(preMovementTime(PreMovementDesc{}, 7, 0), 0.0) << "no distribution, no wait";
}

// Crowds inserted into and removed from a running World (insert.cpp): ids, spawn at the next
// tick, goals walked, removal, events, refusals, determinism across thread counts, timeline; agents
// removed by id (World::removeAgents): events, groups going on without them, refusals, determinism.
#include <gtest/gtest.h>

#include <algorithm>

#include "sim_test_util.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

ScenarioDesc baseScenario() {
  ScenarioDesc d;
  d.seed = 11;
  d.duration = 120.0f;
  d.walkable = {{{0, 0}, {30, 0}, {30, 10}, {0, 10}}};
  PointDesc left;
  left.id = "left";
  left.position = {3, 5};
  left.radius = 1.5f;
  PointDesc right;
  right.id = "right";
  right.position = {27, 5};
  right.radius = 1.5f;
  d.points = {left, right};
  PopulationDesc pop;
  pop.id = "walkers";
  pop.groups = 4;
  pop.spawn.kind = SpawnKind::Polygon;
  pop.spawn.polygon = {{1, 1}, {8, 1}, {8, 9}, {1, 9}};
  pop.goals = {1};
  pop.wander = true;
  pop.radius = 0.25f;
  d.populations = {pop};
  return d;
}

/// A crowd of one flocking group of `size` walking from the right end to a new exit on the left.
CrowdDesc tourCrowd(const ScenarioDesc& world, std::uint32_t size = 3) {
  CrowdDesc c;
  c.id = "tour";
  c.basePoints = static_cast<std::uint32_t>(world.points.size());
  c.basePopulations = static_cast<std::uint32_t>(world.populations.size());
  PointDesc out;
  out.id = "tour-exit";
  out.kind = PointKind::Exit;
  out.position = {1, 5};
  out.radius = 1.0f;
  c.points = {out};
  PopulationDesc pop;
  pop.id = "tourists";
  pop.groups = 1;
  pop.sizeMin = pop.sizeMax = size;
  pop.spawn.kind = SpawnKind::Point;
  pop.spawn.point = 1;  // the world's "right"
  pop.goals = {0, c.basePoints};  // the world's "left", then the crowd's own exit
  pop.radius = 0.2f;
  c.populations = {pop};
  return c;
}

std::unique_ptr<World> make(const ScenarioDesc& d) {
  auto w = World::create(d);
  EXPECT_TRUE(w.ok());
  return std::move(w).value();
}

TEST(InsertCrowd, AgentsAppearAtTheNextTickWithTheNextIds) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  core::TaskSystem tasks(1);
  for (int i = 0; i < 10; ++i) w->step(tasks);
  const auto before = w->takeFrame();
  const std::uint32_t groupsBefore = static_cast<std::uint32_t>(w->groupCount());
  const std::uint32_t spawnedBefore = w->stats().spawned;
  auto index = w->insertCrowd(tourCrowd(d));
  ASSERT_TRUE(index.ok());
  EXPECT_EQ(index.value(), 0u);
  EXPECT_EQ(w->desc().populations.size(), 1u);  // queued: nothing changed yet
  w->step(tasks);
  const auto f = w->takeFrame();
  ASSERT_EQ(f->ids.size(), before->ids.size() + 3);
  std::vector<std::uint32_t> spawned;
  for (const Event& e : f->events) {
    if (e.kind != EventKind::Spawn) continue;
    spawned.push_back(e.agent);
    EXPECT_EQ(e.a, 1u);               // population index: appended after the world's
    EXPECT_EQ(e.b, groupsBefore);     // the next group id
    EXPECT_EQ(e.tick, 10u);
  }
  EXPECT_EQ(spawned, (std::vector<std::uint32_t>{spawnedBefore, spawnedBefore + 1, spawnedBefore + 2}));
  ASSERT_EQ(w->desc().points.size(), 3u);
  EXPECT_EQ(w->desc().points[2].id, "tour-exit");
  EXPECT_EQ(w->desc().populations[1].goals, (std::vector<std::uint32_t>{0, 2}));
  const auto crowds = w->crowds();
  ASSERT_EQ(crowds.size(), 1u);
  EXPECT_TRUE(crowds[0].applied);
  EXPECT_EQ(crowds[0].insertTick, 10u);
  EXPECT_EQ(crowds[0].firstGroup, groupsBefore);
  EXPECT_EQ(crowds[0].present, 3u);
  const auto info = w->groupInfo(w->groupById(groupsBefore));
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->members.size(), 3u);
}

TEST(InsertCrowd, InsertedAgentsWalkTheirGoalsAndExit) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  ASSERT_TRUE(w->insertCrowd(tourCrowd(d)).ok());
  const auto events = test::runEvents(*w, 90.0);
  int reachedLeft = 0, exited = 0;
  for (const Event& e : events) {
    if (e.agent < 4) continue;  // the world's own walkers: ids 0..3
    if (e.kind == EventKind::GoalReached && e.a == 0) ++reachedLeft;
    if (e.kind == EventKind::Exit && e.a == 2) ++exited;
  }
  EXPECT_EQ(reachedLeft, 3);
  EXPECT_EQ(exited, 3);
  EXPECT_EQ(w->stats().exited, 3u);
}

TEST(InsertCrowd, RemovalMakesItsAgentsLeaveAtTheNextTick) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  core::TaskSystem tasks(1);
  ASSERT_TRUE(w->insertCrowd(tourCrowd(d, 5)).ok());
  for (int i = 0; i < 40; ++i) w->step(tasks);
  (void)w->takeFrame();
  ASSERT_EQ(w->stats().active, 9u);
  EXPECT_TRUE(w->removeCrowd("tour"));
  EXPECT_FALSE(w->removeCrowd("tour"));    // already queued
  EXPECT_FALSE(w->removeCrowd("nobody"));
  EXPECT_EQ(w->stats().active, 9u);        // not before the next tick
  w->step(tasks);
  const auto f = w->takeFrame();
  EXPECT_EQ(f->ids.size(), 4u);
  EXPECT_TRUE(std::all_of(f->ids.begin(), f->ids.end(), [](std::uint32_t id) { return id < 4; }));
  int left = 0;
  for (const Event& e : f->events) {
    if (e.kind != EventKind::Exit) continue;
    EXPECT_EQ(e.a, 0xffffffffu);
    EXPECT_EQ(e.b, 0u);
    EXPECT_EQ(e.tick, 40u);
    ++left;
  }
  EXPECT_EQ(left, 5);
  EXPECT_EQ(w->stats().removed, 5u);
  EXPECT_EQ(w->stats().exited, 0u);
  EXPECT_TRUE(w->crowds()[0].removed);
  EXPECT_FALSE(w->removeCrowd("tour"));
  // The world goes on.
  for (int i = 0; i < 20; ++i) w->step(tasks);
  EXPECT_EQ(w->takeFrame()->ids.size(), 4u);
}

TEST(InsertCrowd, RemovingBeforeTheSpawnCancelsIt) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  core::TaskSystem tasks(1);
  CrowdDesc c = tourCrowd(d);
  c.populations[0].start = 30.0f;  // relative to the insertion
  ASSERT_TRUE(w->insertCrowd(c).ok());
  w->step(tasks);
  EXPECT_EQ(w->stats().scheduled, 3u);
  ASSERT_TRUE(w->removeCrowd("tour"));
  w->step(tasks);
  EXPECT_EQ(w->stats().scheduled, 0u);
  for (int i = 0; i < 700; ++i) w->step(tasks);
  EXPECT_EQ(w->stats().spawned, 4u);
}

TEST(InsertCrowd, SpawnTimesCountFromTheInsertion) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  core::TaskSystem tasks(1);
  for (int i = 0; i < 100; ++i) w->step(tasks);  // t = 5 s
  CrowdDesc c = tourCrowd(d);
  c.populations[0].start = 2.0f;
  ASSERT_TRUE(w->insertCrowd(c).ok());
  std::uint64_t spawnTick = 0;
  for (int i = 0; i < 100 && spawnTick == 0; ++i) {
    w->step(tasks);
    const FramePtr f = w->takeFrame();
    for (const Event& e : f->events) if (e.kind == EventKind::Spawn) spawnTick = e.tick;
  }
  EXPECT_EQ(spawnTick, 140u);  // inserted at tick 100, + 2 s / 0.05 s
}

TEST(InsertCrowd, BadCrowdsAreRefusedAndChangeNothing) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  CrowdDesc clash = tourCrowd(d);
  clash.points[0].id = "left";
  clash.populations[0].id = "walkers";
  clash.populations[0].radius = 0.4f;
  clash.populations[0].goals.push_back(9);
  auto r = w->insertCrowd(clash);
  ASSERT_FALSE(r.ok());
  std::vector<std::string> what;
  for (const auto& e : r.errors()) what.push_back(e.pointer + ": " + e.what);
  EXPECT_EQ(what, (std::vector<std::string>{
                      "/points/0/id: point id \"left\" is already taken",
                      "/populations/0/id: population id \"walkers\" is already taken",
                      "/populations/0/goals/2: point index out of range",
                      "/populations/0/radius: body radius 0.400000 m (× passage ratio 0.650000) exceeds the world's navmesh erosion radius 0.162500 m"}));
  CrowdDesc big = tourCrowd(d);
  big.populations[0].groups = 2001;
  big.populations[0].sizeMin = big.populations[0].sizeMax = 5;
  r = w->insertCrowd(big);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors().front().what, "the crowd may spawn 10005 agents");
  EXPECT_EQ(r.errors().front().expected, "at most 10000 agents per insertion");
  ASSERT_TRUE(w->insertCrowd(tourCrowd(d)).ok());
  r = w->insertCrowd(tourCrowd(d));  // the same again: its ids are taken by the queued one
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors().front().what, "crowd id \"tour\" is already taken");
  EXPECT_EQ(w->crowds().size(), 1u);
  EXPECT_EQ(w->desc().points.size(), 2u);
}

TEST(InsertCrowd, FeatureColumnsAreCreatedWhenNeeded) {
  ScenarioDesc d = baseScenario();
  d.populations[0].flocking = false;  // lone walkers: no formation or sociological columns
  auto w = make(d);
  CrowdDesc c = tourCrowd(d, 4);
  c.populations[0].sociological.enabled = true;
  c.populations[0].sociological.changeGroupRate = 1.0f;
  ASSERT_TRUE(w->insertCrowd(c).ok());
  core::TaskSystem tasks(2);
  for (int i = 0; i < 400; ++i) w->step(tasks);
  EXPECT_GT(w->stats().spawned, 4u);
  EXPECT_GT(w->stats().socialMeetings, 0u);
}

/// The world with a timeline: a crowd arriving at 5 s, a second at 8 s, the first leaving at 15 s.
ScenarioDesc timelineScenario() {
  ScenarioDesc d = baseScenario();
  d.populations[0].groups = 12;
  TimelineEntry in;
  in.time = 5.0f;
  in.crowd = tourCrowd(d, 6);
  TimelineEntry in2 = in;
  in2.time = 8.0f;
  in2.crowd.id = "second";
  in2.crowd.points[0].id = "second-exit";
  in2.crowd.populations[0].id = "second-tourists";
  in2.crowd.populations[0].sociological.enabled = true;
  TimelineEntry out;
  out.time = 15.0f;
  out.action = TimelineAction::Remove;
  out.crowdId = "tour";
  d.timeline = {in, in2, out};
  return d;
}

TEST(InsertCrowd, TimelineIsAppliedAtItsTimes) {
  auto w = make(timelineScenario());
  core::TaskSystem tasks(1);
  std::vector<std::uint64_t> spawnTicks, removeTicks;
  while (w->stats().time < 20.0) {
    w->step(tasks);
    const FramePtr f = w->takeFrame();
    for (const Event& e : f->events) {
      if (e.kind == EventKind::Spawn && e.a > 0) spawnTicks.push_back(e.tick);
      if (e.kind == EventKind::Exit && e.a == 0xffffffffu) removeTicks.push_back(e.tick);
    }
  }
  EXPECT_EQ(spawnTicks, (std::vector<std::uint64_t>{100, 100, 100, 100, 100, 100, 160, 160, 160, 160, 160, 160}));
  ASSERT_EQ(w->crowds().size(), 2u);
  EXPECT_EQ(w->crowds()[1].insertTick, 160u);
  EXPECT_EQ(removeTicks.size(), 6u);
  for (auto t : removeTicks) EXPECT_EQ(t, 300u);
  EXPECT_EQ(w->crowds()[1].present, 6u);
}

TEST(InsertCrowd, TimelineIsDeterministicAcrossThreadCounts) {
  const ScenarioDesc d = timelineScenario();
  std::uint64_t hash[2] = {0, 0};
  for (int t = 1; t <= 2; ++t) {
    auto w = make(d);
    core::TaskSystem tasks(t);
    for (int i = 0; i < 500; ++i) w->step(tasks);
    hash[t - 1] = w->stateHash();
  }
  EXPECT_EQ(hash[0], hash[1]);
}

TEST(InsertCrowd, ApiInsertionsAreDeterministicAcrossThreadCounts) {
  const ScenarioDesc d = baseScenario();
  std::uint64_t hash[2] = {0, 0};
  for (int t = 1; t <= 2; ++t) {
    auto w = make(d);
    core::TaskSystem tasks(t);
    for (int i = 0; i < 300; ++i) {
      if (i == 20) ASSERT_TRUE(w->insertCrowd(tourCrowd(d, 7)).ok());
      if (i == 200) ASSERT_TRUE(w->removeCrowd("tour"));
      w->step(tasks);
    }
    hash[t - 1] = w->stateHash();
  }
  EXPECT_EQ(hash[0], hash[1]);
}

TEST(InsertCrowd, AWorldWithoutCrowdsIsUnchanged) {
  // Two worlds, one given an empty timeline and asked for crowds: the same trajectories.
  const ScenarioDesc d = baseScenario();
  auto a = make(d);
  auto b = make(d);
  core::TaskSystem tasks(1);
  EXPECT_TRUE(b->crowds().empty());
  EXPECT_FALSE(b->removeCrowd("tour"));
  for (int i = 0; i < 200; ++i) {
    a->step(tasks);
    b->step(tasks);
  }
  EXPECT_EQ(a->stateHash(), b->stateHash());
}

TEST(RemoveAgents, TheyLeaveAtTheNextTickAndTheirGroupGoesOnWithANewLeader) {
  const ScenarioDesc d = baseScenario();
  auto w = make(d);
  core::TaskSystem tasks(1);
  ASSERT_TRUE(w->insertCrowd(tourCrowd(d, 5)).ok());
  for (int i = 0; i < 40; ++i) w->step(tasks);
  (void)w->takeFrame();
  const GroupId tour = w->groupById(4);  // the crowd's group: after the scenario's four
  const std::optional<GroupInfo> before = w->groupInfo(tour);
  ASSERT_TRUE(before && before->members.size() == 5u);
  const std::uint32_t leader = before->leader, other = before->members[3];
  const std::vector<std::uint32_t> ids{other, leader};
  ASSERT_TRUE(w->removeAgents(ids).ok());
  EXPECT_EQ(w->stats().active, 9u) << "not before the next tick";
  w->step(tasks);
  const FramePtr f = w->takeFrame();
  EXPECT_EQ(f->size(), 7u);
  std::vector<std::uint32_t> left;
  for (const Event& e : f->events) {
    if (e.kind != EventKind::Exit) continue;
    EXPECT_EQ(e.a, 0xffffffffu);
    EXPECT_EQ(e.b, 0xffffffffu);
    EXPECT_EQ(e.tick, 40u);
    left.push_back(e.agent);
  }
  EXPECT_EQ(left, ids) << "in the order asked";
  EXPECT_EQ(w->stats().removed, 2u);
  EXPECT_EQ(w->stats().exited, 0u);
  EXPECT_FALSE(w->agentInfo(leader).has_value());
  const std::optional<GroupInfo> after = w->groupInfo(tour);
  ASSERT_EQ(after->members.size(), 3u);
  EXPECT_EQ(after->leader, after->members.front()) << "the lowest id left leads, as after an exit";
  EXPECT_EQ(w->crowds()[0].present, 3u);
  // The three walk on to their exit.
  test::runEvents(*w, 120.0);
  EXPECT_EQ(w->stats().exited, 3u);
}

TEST(RemoveAgents, BadIdsAreRefusedEachNamedAndNothingIsQueued) {
  auto w = make(baseScenario());
  core::TaskSystem tasks(1);
  w->step(tasks);
  const std::vector<std::uint32_t> bad{1, 99, 1, 2};
  const core::Status refused = w->removeAgents(bad);
  ASSERT_FALSE(refused.ok());
  ASSERT_EQ(refused.errors().size(), 2u);
  EXPECT_EQ(refused.errors()[0].pointer, "/1");
  EXPECT_NE(refused.errors()[0].what.find("99"), std::string::npos);
  EXPECT_EQ(refused.errors()[1].pointer, "/2");
  EXPECT_NE(refused.errors()[1].what.find("twice"), std::string::npos);
  const std::vector<std::uint32_t> one{3};
  ASSERT_TRUE(w->removeAgents(one).ok());
  const core::Status again = w->removeAgents(one);
  ASSERT_FALSE(again.ok());
  EXPECT_NE(again.errors()[0].what.find("already queued"), std::string::npos);
  w->step(tasks);
  EXPECT_EQ(w->stats().active, 3u) << "only the one accepted";
  EXPECT_FALSE(w->removeAgents(one).ok()) << "gone now";
  EXPECT_TRUE(w->removeAgents({}).ok());
}

TEST(RemoveAgents, RemovalsAreDeterministicAcrossThreadCounts) {
  const ScenarioDesc d = baseScenario();
  std::uint64_t hash[3] = {0, 0, 0};
  for (int t : {1, 2, 4}) {
    auto w = make(d);
    core::TaskSystem tasks(t);
    for (int i = 0; i < 300; ++i) {
      if (i == 20) ASSERT_TRUE(w->insertCrowd(tourCrowd(d, 7)).ok());
      if (i == 100) ASSERT_TRUE(w->removeAgents(std::vector<std::uint32_t>{0, 6, 8}).ok());
      if (i == 150) ASSERT_TRUE(w->removeAgents(std::vector<std::uint32_t>{4}).ok());
      w->step(tasks);
    }
    EXPECT_EQ(w->stats().removed, 4u);
    hash[t == 4 ? 2 : t - 1] = w->stateHash();
  }
  EXPECT_EQ(hash[0], hash[1]);
  EXPECT_EQ(hash[0], hash[2]);
}

}  // namespace
}  // namespace throng::sim

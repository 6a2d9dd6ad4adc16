// Tests for libs/sim/src/goals.hpp: GoalWriter on hand-built state (no World) — a goal's target is
// drawn inside the point's region and occupies one of its sub-regions, which is released when the
// agent moves on; pending goal changes are applied in row order; only an exit limits the target to
// its near side. And World runs: agents in front of one end of a long exit strip leave through
// it near straight ahead; waypoint choices split a population by shares or least targeted, per
// group, the same for any thread count, each group's choice recorded by a WaypointChosen event.
#include "goals.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "goal_world.hpp"
#include "throng/sim/world.hpp"

using namespace throng;
using namespace throng::sim;

using test::GoalWorld;

TEST(Goals, PointRegionsCutEveryPointIntoSubregions) {
  const GoalWorld w(0);
  ASSERT_EQ(w.regions.subOffset.size(), 3u);
  EXPECT_GT(w.regions.subOffset[1], w.regions.subOffset[0]) << "a 3 m disc has sub-regions";
  EXPECT_GT(w.regions.subOffset[2], w.regions.subOffset[1]);
  EXPECT_EQ(w.regions.occupancy.size(), w.regions.subregions.size());
  EXPECT_EQ(w.occupied(0) + w.occupied(1), 0u) << "nobody targets them yet";
  ASSERT_EQ(w.regions.bounds.size(), 2u);
  EXPECT_FLOAT_EQ(w.regions.bounds[1].min.x, 12.0f);
}

TEST(Goals, SetGoalDrawsATargetInsideThePointAndReleasesTheOldSubregion) {
  GoalWorld w(1);
  GoalWriter goals = w.writer();
  goals.setGoal(0, 0);
  EXPECT_EQ(w.agents.goalCursor[0], 0u);
  EXPECT_EQ(w.agents.goalState[0], GoalState::Seeking);
  EXPECT_EQ(w.agents.needPath[0], 1u);
  EXPECT_TRUE(insideRegion(w.desc.points[0], w.agents.targetX[0], w.agents.targetY[0]))
      << w.agents.targetX[0] << ", " << w.agents.targetY[0];
  const std::int32_t first = w.agents.targetSub[0];
  ASSERT_GE(first, static_cast<std::int32_t>(w.regions.subOffset[0]));
  ASSERT_LT(first, static_cast<std::int32_t>(w.regions.subOffset[1]));
  EXPECT_EQ(w.regions.occupancy[static_cast<std::size_t>(first)], 1u);
  EXPECT_EQ(w.agents.targetDraws[0], 1u) << "one draw from the target stream";

  goals.advanceGoal(0);
  EXPECT_EQ(w.agents.goalCursor[0], 1u);
  EXPECT_TRUE(insideRegion(w.desc.points[1], w.agents.targetX[0], w.agents.targetY[0]));
  EXPECT_EQ(w.regions.occupancy[static_cast<std::size_t>(first)], 0u) << "the old sub-region is released";
  EXPECT_EQ(w.occupied(0), 0u);
  EXPECT_EQ(w.occupied(1), 1u);

  goals.advanceGoal(0);  // past the last goal, no wandering: done, standing where it is
  EXPECT_EQ(w.agents.goalState[0], GoalState::Done);
  EXPECT_EQ(w.agents.mode[0], AgentMode::Waiting);
  EXPECT_EQ(w.agents.targetSub[0], -1);
  EXPECT_EQ(w.occupied(1), 0u);
  EXPECT_FLOAT_EQ(w.agents.targetX[0], 10.0f);
  EXPECT_TRUE(w.events.empty());
}

TEST(Goals, AgentsAimingAtOnePointSpreadOverItsSubregions) {
  GoalWorld w(4);
  GoalWriter goals = w.writer();
  for (std::size_t r = 0; r < 4; ++r) goals.setGoal(r, 0);
  EXPECT_EQ(w.occupied(0), 4u);
  EXPECT_LT(*std::max_element(w.regions.occupancy.begin(), w.regions.occupancy.end()), 4u)
      << "an occupied sub-region is less likely to be picked: not all four in one";
  for (std::size_t r = 0; r < 4; ++r) goals.releaseTarget(r);
  EXPECT_EQ(w.occupied(0), 0u);
  for (std::size_t r = 0; r < 4; ++r) EXPECT_EQ(w.agents.targetSub[r], -1);
  goals.releaseTarget(0);  // twice: nothing more to release
  EXPECT_EQ(w.occupied(0), 0u);
}

TEST(Goals, ApplyPendingGoalsAdvancesTheListedRowsAndClearsTheirFlags) {
  GoalWorld w(3);
  GoalWriter goals = w.writer();
  for (std::size_t r = 0; r < 3; ++r) goals.setGoal(r, 0);
  std::vector<ChunkOutput> chunks(2);
  w.agents.goalPending[0] = GoalPending::NextGoal;
  w.agents.goalPending[2] = GoalPending::NextWanderTarget;
  chunks[0].pendingRows = {0};
  chunks[1].pendingRows = {2};
  goals.applyPendingGoals(chunks);
  EXPECT_EQ(w.agents.goalCursor[0], 1u);
  EXPECT_EQ(w.agents.goalCursor[1], 0u) << "not listed: unchanged";
  EXPECT_EQ(w.agents.goalCursor[2], 2u) << "past the list; the population does not wander: done";
  EXPECT_EQ(w.agents.goalState[2], GoalState::Done);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_EQ(w.agents.goalPending[r], GoalPending::None);
  EXPECT_TRUE(chunks[0].pendingRows.empty() && chunks[1].pendingRows.empty());
  EXPECT_EQ(w.occupied(0), 1u);
  EXPECT_EQ(w.occupied(1), 1u);
}

TEST(Goals, OnlyAnExitLimitsTheTargetToItsNearSide) {
  // 40 agents 20 m in front of the left end of a 200 m strip pick in turn: as an exit, among the
  // cells at most 5 % farther than the nearest (within ~7 m of straight ahead); as an interest or
  // action point, over the whole region (Musse et al. §3.1.3), free cells first, so far along it.
  const auto subs = crowd::divideRegion(crowd::Region::poly(test::rect(0, 20, 200, 21)));
  const auto farthest = [&](PointKind kind) {
    std::vector<std::uint32_t> occupancy(subs.size(), 0);
    core::Rng rng(3, 3, core::RngPurpose::Target);
    float far = 0.0f;
    for (int m = 0; m < 40; ++m) {
      const std::size_t i = crowd::pickSubregion(subs, {1, 0}, occupancy, rng, pickParams(kind));
      ++occupancy[i];
      far = std::max(far, subs[i].centre.x);
    }
    return far;
  };
  EXPECT_LT(farthest(PointKind::Exit), 10.0f);
  EXPECT_GT(farthest(PointKind::Interest), 60.0f);
  EXPECT_GT(farthest(PointKind::Action), 60.0f);
}

TEST(Goals, AgentsInFrontOfOneEndOfALongExitStripLeaveNearStraightAhead) {
  // A 200 m wide room whose whole far wall is the exit (RiMEA 7's wide exit): 20 agents start in
  // front of its left end, 7..10 m from it. Each aims at a spot of the strip at most 2 m farther
  // than the nearest (crowd::PickParams::detourMin), so it crosses the strip within ~8 m of where
  // it started; the old occupancy-first pick gave each a free 2 m cell, up to ~40 m along.
  ScenarioDesc d;
  d.seed = 11;
  d.walkable = {test::rect(0, 0, 200, 12)};
  PointDesc exit;
  exit.id = "exit";
  exit.kind = PointKind::Exit;
  exit.polygon = test::rect(0, 11, 200, 12);
  exit.position = {100, 11.5f};
  d.points = {exit};
  PopulationDesc p;
  p.id = "walkers";
  p.groups = 20;
  p.spawn.polygon = test::rect(1, 1, 5, 4);
  p.goals = {0};
  d.populations = {p};
  auto created = World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  World& w = *created.value();
  const core::TaskSystem tasks(1);
  std::map<std::uint32_t, float> lastX;
  int exited = 0;
  while (!w.finished() && w.stats().time < 60.0) {
    w.step(tasks);
    const FramePtr f = w.takeFrame();
    for (const Event& e : f->events) {
      if (e.kind != EventKind::Exit) continue;
      ++exited;
      ASSERT_TRUE(lastX.contains(e.agent));
      EXPECT_LT(lastX[e.agent], 14.0f) << "agent " << e.agent << " walked along the strip";
    }
    for (std::size_t i = 0; i < f->size(); ++i) lastX[f->ids[i]] = f->posX[i];
  }
  EXPECT_EQ(exited, 20);
}

namespace {

/// An exit point "exit" over the rectangle x0..x1 × y0..y1.
PointDesc exitOver(float x0, float y0, float x1, float y1) {
  PointDesc exit;
  exit.id = "exit";
  exit.kind = PointKind::Exit;
  exit.polygon = test::rect(x0, y0, x1, y1);
  exit.position = {(x0 + x1) / 2, (y0 + y1) / 2};
  return exit;
}

/// A 30 × 20 m hall: three interest stands (discs at x = 15) and the east wall as exit; `groups`
/// groups of `size` pick a stand by `choice` (options: the stands, slot 0), then leave.
ScenarioDesc standsHall(std::uint32_t groups, std::uint32_t size, GoalSplit split, std::vector<float> shares) {
  ScenarioDesc d;
  d.seed = 3;
  d.walkable = {test::rect(0, 0, 30, 20)};
  for (const float y : {4.0f, 10.0f, 16.0f}) {
    PointDesc stand;
    stand.id = "stand" + std::to_string(d.points.size());
    stand.position = {15, y};
    stand.radius = 1.5f;
    d.points.push_back(stand);
  }
  d.points.push_back(exitOver(29.5f, 0, 30, 20));
  PopulationDesc p;
  p.id = "visitors";
  p.groups = groups;
  p.sizeMin = p.sizeMax = size;
  p.spawn.polygon = test::rect(0.5f, 0.5f, 6, 19.5f);
  p.goals = {0, 3};
  GoalChoiceDesc c;
  c.options = {0, 1, 2};
  c.split = split;
  c.shares = std::move(shares);
  p.goalChoices = {c};
  d.populations = {p};
  return d;
}

/// Runs `d` on `threads` threads until 2 s have passed; per agent (stable id), the stand it heads for.
std::map<std::uint32_t, std::uint32_t> standOfEachAgent(const ScenarioDesc& d, unsigned threads) {
  auto created = World::create(d);
  EXPECT_TRUE(created.ok()) << core::formatAll(created.errors());
  World& w = *created.value();
  const core::TaskSystem tasks(threads);
  while (w.stats().time < 2.0) {
    w.step(tasks);
    (void)w.takeFrame();
  }
  std::map<std::uint32_t, std::uint32_t> stand;
  for (std::uint32_t id = 0; id < w.stats().spawned; ++id) {
    if (const auto info = w.agentInfo(id)) stand[id] = info->goalPoint;
  }
  return stand;
}

}  // namespace

TEST(Goals, ASharesSplitSendsGroupsByTheShares) {
  // 120 groups, shares 2 : 1 : 1 — about 60, 30 and 30 (binomial sd ≈ 5.5 and 4.7).
  const auto stand = standOfEachAgent(standsHall(120, 1, GoalSplit::Shares, {2, 1, 1}), 1);
  ASSERT_EQ(stand.size(), 120u);
  std::map<std::uint32_t, int> count;
  for (const auto& [id, point] : stand) ++count[point];
  EXPECT_NEAR(count[0], 60, 15);
  EXPECT_NEAR(count[1], 30, 12);
  EXPECT_NEAR(count[2], 30, 12);
}

TEST(Goals, ALeastTargetedSplitBalancesTheStandsAndKeepsGroupsTogether) {
  // 30 pairs: each pair takes the stand the fewest head for when it appears, so 20 agents each,
  // and both members of a pair the same stand.
  const auto stand = standOfEachAgent(standsHall(30, 2, GoalSplit::LeastTargeted, {}), 1);
  ASSERT_EQ(stand.size(), 60u);
  std::map<std::uint32_t, int> count;
  for (const auto& [id, point] : stand) ++count[point];
  EXPECT_EQ(count[0], 20);
  EXPECT_EQ(count[1], 20);
  EXPECT_EQ(count[2], 20);
  for (std::uint32_t id = 0; id < 60; id += 2) EXPECT_EQ(stand.at(id), stand.at(id + 1)) << "pair " << id / 2;
}

TEST(Goals, WaypointChoicesAreTheSameForAnyThreadCount) {
  const ScenarioDesc d = standsHall(200, 1, GoalSplit::Shares, {1, 3, 1});
  EXPECT_EQ(standOfEachAgent(d, 1), standOfEachAgent(d, 4));
}

TEST(Goals, EachGroupReachingAChoiceRecordsTheWaypointItChoseAndWalksThere) {
  // Pairs pass a plain waypoint (slot 0) and then choose a stand (slot 1, least targeted): one
  // WaypointChosen event per pair that reaches the choice, naming its leader, the stand and slot 1,
  // and both members head for that stand and no other.
  ScenarioDesc d = standsHall(24, 2, GoalSplit::LeastTargeted, {});
  PointDesc entry;
  entry.id = "entry";
  entry.position = {9, 10};
  entry.radius = 1.5f;
  d.points.push_back(entry);
  PopulationDesc& p = d.populations.front();
  p.goals = {4, 0, 3};  // entry, a stand (chosen), the exit
  p.goalChoices.front().slot = 1;
  auto created = World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  World& w = *created.value();
  const core::TaskSystem tasks(1);
  std::map<std::uint32_t, std::uint32_t> chosenBy;        // group -> stand its event names
  std::map<std::uint32_t, std::set<std::uint32_t>> headed;  // agent -> stands it headed for
  std::map<std::uint32_t, std::uint32_t> groupOf;
  while (!w.finished() && w.stats().time < 120.0) {
    w.step(tasks);
    const auto f = w.takeFrame();
    for (const Event& e : f->events) {
      if (e.kind != EventKind::WaypointChosen) continue;
      const auto leader = w.agentInfo(e.agent);
      ASSERT_TRUE(leader) << "the leader is present when its group chooses";
      EXPECT_EQ(e.b, 1u) << "the choice's slot";
      EXPECT_LT(e.a, 3u) << "a stand";
      EXPECT_TRUE(chosenBy.emplace(leader->group, e.a).second) << "group " << leader->group << " chose twice";
    }
    for (std::uint32_t id = 0; id < w.stats().spawned; ++id) {
      const auto info = w.agentInfo(id);
      if (!info) continue;
      groupOf[id] = info->group;
      if (info->goalPoint < 3) headed[id].insert(info->goalPoint);
    }
  }
  ASSERT_TRUE(w.finished()) << "everyone left within 120 s";
  EXPECT_EQ(chosenBy.size(), 24u) << "every pair reached the choice once";
  EXPECT_EQ(headed.size(), 48u);
  std::map<std::uint32_t, int> perStand;
  for (const auto& [id, stands] : headed) {
    ASSERT_TRUE(chosenBy.contains(groupOf.at(id))) << "agent " << id << " headed for a stand its group never chose";
    EXPECT_EQ(stands, std::set<std::uint32_t>{chosenBy.at(groupOf.at(id))}) << "agent " << id;
    ++perStand[*stands.begin()];
  }
  for (std::uint32_t stand = 0; stand < 3; ++stand) EXPECT_GT(perStand[stand], 0) << "stand " << stand;
}

TEST(Goals, WaypointChosenEventsAreTheSameForAnyThreadCount) {
  const ScenarioDesc d = standsHall(200, 2, GoalSplit::LeastTargeted, {});
  const auto events = [&](unsigned threads) {
    auto created = World::create(d);
    EXPECT_TRUE(created.ok());
    World& w = *created.value();
    core::TaskSystem tasks(threads);
    tasks.setGrainLimit(4);
    std::vector<std::array<std::uint64_t, 4>> out;
    while (w.stats().time < 3.0) {
      w.step(tasks);
      // The frame held while its events are read (a range-for over takeFrame()->events would read
      // them after the frame is freed: the temporary dies before the loop body runs).
      const auto frame = w.takeFrame();
      for (const Event& e : frame->events) {
        if (e.kind == EventKind::WaypointChosen) out.push_back({e.tick, e.agent, e.a, e.b});
      }
    }
    return out;
  };
  const auto one = events(1);
  EXPECT_EQ(one.size(), 200u);
  EXPECT_EQ(one, events(4));
}

// A target drawn where the navmesh's erosion has no floor is put 3 cm inside the mesh, not on its
// edge: on the edge, a sight line along it held from one spot and not the next, and a walker 6 cm
// short of an exit turned back and forth between its target and the corner before it for ever
// (NIST 2.9 in session 41). Red without kTargetInset (the target then lies on the edge).
TEST(Goals, ATargetInTheNavmeshMarginLiesJustInsideTheMeshNotOnItsEdge) {
  GoalWorld w(1);
  w.desc.points[0].position = {5.0f, 0.1f};
  w.desc.points[0].radius = 0.08f;  // wholly inside the eroded margin along y = 0
  w.regions = PointRegions{};
  for (const PointDesc& p : w.desc.points) w.regions.add(p);
  GoalWriter goals = w.writer();
  goals.setGoal(0, 0);
  const core::Vec2 t{w.agents.targetX[0], w.agents.targetY[0]};
  const auto on = w.query->nearest(t, 0.1f);
  ASSERT_TRUE(on.has_value());
  EXPECT_LT(core::length(on->first - t), 1e-4f) << "the target is on the mesh: " << t.x << ", " << t.y;
  const auto below = w.query->nearest({t.x, t.y - 0.02f}, 0.1f);
  ASSERT_TRUE(below.has_value());
  EXPECT_LT(core::length(below->first - core::Vec2{t.x, t.y - 0.02f}), 1e-4f) << "2 cm nearer the wall is still floor";
  const auto edge = w.query->nearest({t.x, t.y - 0.05f}, 0.1f);
  ASSERT_TRUE(edge.has_value());
  EXPECT_GT(core::length(edge->first - core::Vec2{t.x, t.y - 0.05f}), 1e-3f) << "5 cm nearer is past the edge";
}

namespace {

/// 12 walkers cross five checkpoints set across a 40 × 6 m corridor (full width, 6 m apart) aiming
/// by `aim`, then leave by its east end. Per walker, how far across the way (y) it strayed from
/// where it stood after the first second, the largest over its walk between the checkpoints.
std::vector<float> strayAcrossCheckpoints(PointAim aim) {
  ScenarioDesc d;
  d.seed = 5;
  d.walkable = {test::rect(0, 0, 40, 6)};
  for (int k = 0; k < 5; ++k) {
    PointDesc gate;
    gate.id = "gate" + std::to_string(k);
    const float x = 8.0f + 6.0f * static_cast<float>(k);
    gate.polygon = test::rect(x, 0, x + 0.4f, 6);
    gate.position = {x + 0.2f, 3};
    gate.aim = aim;
    d.points.push_back(gate);
  }
  d.points.push_back(exitOver(39.5f, 0, 40, 6));
  PopulationDesc p;
  p.id = "walkers";
  p.groups = 12;
  p.spawn.polygon = test::rect(0.5f, 0.5f, 4, 5.5f);
  p.goals = {0, 1, 2, 3, 4, 5};
  d.populations = {p};
  auto created = World::create(d);
  EXPECT_TRUE(created.ok()) << core::formatAll(created.errors());
  World& w = *created.value();
  const core::TaskSystem tasks(1);
  std::map<std::uint32_t, float> start, stray;
  while (!w.finished() && w.stats().time < 60.0) {
    w.step(tasks);
    const FramePtr f = w.takeFrame();
    for (std::size_t i = 0; i < f->size(); ++i) {
      const std::uint32_t id = f->ids[i];
      if (w.stats().time <= 1.0) start[id] = f->posY[i];
      if (f->posX[i] > 8.0f && f->posX[i] < 32.4f) stray[id] = std::max(stray[id], std::abs(f->posY[i] - start.at(id)));
    }
  }
  EXPECT_TRUE(w.finished()) << "everyone out within a minute";
  std::vector<float> out;
  for (const auto& [id, s] : stray) out.push_back(s);
  return out;
}

float mean(const std::vector<float>& v) {
  float s = 0.0f;
  for (const float x : v) s += x;
  return v.empty() ? 0.0f : s / static_cast<float>(v.size());
}

}  // namespace

TEST(Goals, WalkersAimingAtCheckpointsByLaneKeepTheirPlaceAcrossTheWay) {
  // "aim": "lane" — each checkpoint is aimed at where the way from the previous one, moved across to
  // the walker, crosses it, so nobody crosses the corridor between them. The default spread draws
  // a spot anywhere across each (Musse et al.'s sub-regions): walkers weave from side to side.
  const std::vector<float> lane = strayAcrossCheckpoints(PointAim::Lane);
  const std::vector<float> spread = strayAcrossCheckpoints(PointAim::Spread);
  ASSERT_EQ(lane.size(), 12u);
  ASSERT_EQ(spread.size(), 12u);
  EXPECT_LT(mean(lane), 0.3f);
  EXPECT_LT(*std::max_element(lane.begin(), lane.end()), 0.8f);
  EXPECT_GT(mean(spread), 1.0f) << "the contrast: spread spots make them cross the way";
}

// Tests of the crowd model's paths inside the World (decide.cpp / groups.cpp with libs/crowd):
// sub-region targets, Bézier seek-goal with its navmesh fallback, automatic goals.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "sim_test_util.hpp"
#include "throng/sim/world.hpp"

using namespace throng;
using throng::sim::test::runEvents;

namespace {

/// A 30 m × 20 m room with a 4 m × 8 m block in the middle.
sim::ScenarioDesc room() {
  sim::ScenarioDesc d;
  d.name = "room";
  d.seed = 5;
  d.walkable = {{{0, 0}, {30, 0}, {30, 20}, {0, 20}}};
  d.obstacles = {{{13, 6}, {17, 6}, {17, 14}, {13, 14}}};
  return d;
}

sim::PointDesc disc(const char* id, sim::PointKind kind, core::Vec2 at, float radius) {
  sim::PointDesc p;
  p.id = id;
  p.kind = kind;
  p.position = at;
  p.radius = radius;
  return p;
}


}  // namespace

TEST(CrowdPaths, GroupMembersSpreadOverAnActionPointsRegion) {
  sim::ScenarioDesc d = room();
  sim::PointDesc painting = disc("painting", sim::PointKind::Action, {25, 10}, 2.0f);
  painting.stop = true;
  painting.orientation = {1, 0};
  painting.action = "look";
  painting.actionDuration = 20.0f;
  d.points = {painting};
  sim::PopulationDesc p;
  p.id = "visitors";
  p.groups = 1;
  p.sizeMin = p.sizeMax = 4;
  p.spawn.kind = sim::SpawnKind::Position;
  p.spawn.position = {4, 10};
  p.goals = {0};
  d.populations = {p};
  auto w = sim::World::create(d);
  ASSERT_TRUE(w.ok());
  core::TaskSystem tasks(1);
  int acting = 0;
  for (int i = 0; i < 1200 && acting < 4; ++i) {
    w.value()->step(tasks);
    const auto f = w.value()->takeFrame();
    acting = 0;
    for (auto m : f->mode) acting += m == sim::AgentMode::Acting;
  }
  ASSERT_EQ(acting, 4) << "everyone reached the painting";
  const auto f = w.value()->takeFrame();
  for (std::size_t i = 0; i < f->size(); ++i) {
    EXPECT_LT(core::distance(core::Vec2{f->posX[i], f->posY[i]}, core::Vec2{25, 10}), 2.0f + 0.3f) << "inside the region";
    EXPECT_NEAR(f->oriX[i], 1.0f, 1e-5f) << "facing the painting";
    for (std::size_t j = i + 1; j < f->size(); ++j) {
      // Distinct sub-regions: nobody queues behind anyone for the same spot.
      EXPECT_GT(core::distance(core::Vec2{f->posX[i], f->posY[i]}, core::Vec2{f->posX[j], f->posY[j]}), 0.4f);
    }
  }
  // The recording says which clip plays: the action, at a phase that grows while acting.
  ASSERT_EQ(f->clip.size(), f->size());
  for (std::size_t i = 0; i < f->size(); ++i) {
    EXPECT_EQ(f->clip[i], 2u) << "clip 2 = the first action clip after idle and walk";
    EXPECT_GE(f->phase[i], 0.0f);
    EXPECT_LT(f->phase[i], 1.0f);
  }
}

TEST(CrowdPaths, BezierSeekGoalStaysInsideAndFallsBackBehindWalls) {
  sim::ScenarioDesc d = room();
  // The exit sits in a cup open to the east only: no single curve from the west side reaches it.
  d.obstacles.push_back({{21, 4}, {28, 4}, {28, 5}, {21, 5}});
  d.obstacles.push_back({{21, 15}, {28, 15}, {28, 16}, {21, 16}});
  d.obstacles.push_back({{21, 4}, {22, 4}, {22, 16}, {21, 16}});
  d.points = {disc("east", sim::PointKind::Exit, {25, 10}, 1.2f), disc("north", sim::PointKind::Interest, {5, 17}, 1.5f)};
  sim::PopulationDesc p;
  p.id = "strollers";
  p.groups = 12;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = {{1, 1}, {8, 1}, {8, 19}, {1, 19}};
  p.goals = {1, 0};  // north (a curve fits), then the exit in the cup (none does)
  p.bezierPaths = true;
  p.radius = 0.2f;
  d.populations = {p};
  auto w = sim::World::create(d);
  ASSERT_TRUE(w.ok());
  core::TaskSystem tasks(2);
  int fallbacks = 0;
  float closest = 1e9f;
  while (w.value()->stats().time < 90 && !w.value()->finished()) {
    w.value()->step(tasks);
    const auto f = w.value()->takeFrame();
    for (const auto& e : f->events) fallbacks += e.kind == sim::EventKind::PathFallback;
    for (std::size_t i = 0; i < f->size(); ++i) {
      const float dx = std::max({13.0f - f->posX[i], 0.0f, f->posX[i] - 17.0f});
      const float dy = std::max({6.0f - f->posY[i], 0.0f, f->posY[i] - 14.0f});
      closest = std::min(closest, std::hypot(dx, dy));
    }
  }
  EXPECT_EQ(w.value()->stats().exited, 12u) << "every curve (or its fallback) leads out";
  EXPECT_GE(closest, 0.2f) << "no body ever overlaps the block";
  EXPECT_GE(fallbacks, 12) << "the exit in the cup has no single curve: navmesh fallback, logged for each agent";
}

TEST(CrowdPaths, AutomaticGoalsEndAtAnActionPointThroughNearbyInterestPoints) {
  sim::ScenarioDesc d = room();
  d.obstacles.clear();
  sim::PointDesc statue = disc("statue", sim::PointKind::Action, {26, 10}, 1.5f);
  statue.stop = true;
  statue.action = "look";
  statue.actionDuration = 3.0f;
  d.points = {disc("hall", sim::PointKind::Interest, {15, 10}, 2.0f), statue};
  sim::PopulationDesc p;
  p.id = "auto";
  p.groups = 3;
  p.sizeMin = p.sizeMax = 2;
  p.spawn.kind = sim::SpawnKind::Position;
  p.spawn.position = {3, 10};
  p.autoGoals = true;
  p.autoNearDistance = 3.0f;
  d.populations = {p};
  auto w = sim::World::create(d);
  ASSERT_TRUE(w.ok());
  const auto events = runEvents(*w.value(), 90, 2);
  std::map<std::uint32_t, std::vector<std::uint32_t>> reached;  // agent → points in order
  for (const auto& e : events) {
    if (e.kind == sim::EventKind::GoalReached || e.kind == sim::EventKind::ActionStart) reached[e.agent].push_back(e.a);
  }
  ASSERT_EQ(reached.size(), 6u);
  for (const auto& [agent, points] : reached) {
    ASSERT_EQ(points.size(), 2u) << "agent " << agent;
    EXPECT_EQ(points[0], 0u) << "the interest point on the straight way is snapped in";
    EXPECT_EQ(points[1], 1u) << "the final goal is the (only) action point";
  }
}

// Tests for libs/bench/src/scenarios.cpp: every bench layout builds a valid world of the asked size
// (the navmesh builds, World::create accepts it, exactly that many agents spawn at tick 0, inside
// the square and off the pillars, and they walk); names round-trip; the square keeps 1 agent/m²;
// start points for the baseline land on the navmesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "throng/bench/scenarios.hpp"
#include "throng/core/parallel.hpp"
#include "throng/sim/world.hpp"

namespace throng::bench {
namespace {

/// Whether `p` is inside one of the scenario's obstacles (the pillars: axis-aligned squares).
bool insidePillar(const sim::ScenarioDesc& desc, core::Vec2 p) {
  for (const core::Polygon& pillar : desc.obstacles) {
    float x0 = pillar[0].x, x1 = pillar[0].x, y0 = pillar[0].y, y1 = pillar[0].y;
    for (const core::Vec2 q : pillar) {
      x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
    }
    if (p.x > x0 && p.x < x1 && p.y > y0 && p.y < y1) return true;
  }
  return false;
}

class BenchScenario : public ::testing::TestWithParam<std::tuple<Layout, std::size_t>> {};

TEST_P(BenchScenario, BuildsAValidWorldOfTheAskedSize) {
  const auto [layout, agents] = GetParam();
  const sim::ScenarioDesc desc = makeScenario(layout, agents, 7);
  EXPECT_EQ(desc.name, std::string("bench-") + kLayoutNames[static_cast<int>(layout)] + "-" + std::to_string(agents));
  EXPECT_FLOAT_EQ(desc.dt, kDt);
  std::size_t described = 0;
  for (const auto& p : desc.populations) {
    EXPECT_EQ(p.sizeMin, p.sizeMax) << p.id;
    EXPECT_TRUE(p.wander) << p.id;
    described += static_cast<std::size_t>(p.groups) * p.sizeMin;
  }
  EXPECT_EQ(described, agents);
  // Pillars (1 m every 8 m, from 4 m in) only in the navmesh layout, and only where they fit.
  EXPECT_EQ(desc.obstacles.empty(), layout != Layout::Navmesh || squareSide(agents) < kPillarSpacing / 2 + kPillarSize / 2);
  if (layout == Layout::Navmesh && agents == 400) EXPECT_EQ(desc.obstacles.size(), 4u);  // 20 m: at 4 and 12 m

  auto navmesh = buildNavMesh(desc);
  ASSERT_TRUE(navmesh.ok()) << core::formatAll(navmesh.errors());
  auto world = sim::World::create(desc, navmesh.value());
  ASSERT_TRUE(world.ok()) << core::formatAll(world.errors());
  core::TaskSystem tasks(1);
  for (int i = 0; i < 20; ++i) world.value()->step(tasks);
  const sim::WorldStats& stats = world.value()->stats();
  EXPECT_EQ(stats.spawned, agents);
  EXPECT_EQ(stats.active, agents);
  EXPECT_EQ(stats.scheduled, 0u);
  EXPECT_GT(stats.walkedDistance, 0.0);  // wanderers walk
  const float side = squareSide(agents);
  for (std::uint32_t id = 0; id < agents; ++id) {
    const auto info = world.value()->agentInfo(id);
    ASSERT_TRUE(info.has_value()) << "agent " << id;
    EXPECT_TRUE(info->position.x > 0 && info->position.x < side && info->position.y > 0 && info->position.y < side)
        << "agent " << id << " at " << info->position.x << ", " << info->position.y;
    EXPECT_FALSE(insidePillar(desc, info->position)) << "agent " << id;
  }
}

INSTANTIATE_TEST_SUITE_P(LayoutsAndSizes, BenchScenario,
                         ::testing::Combine(::testing::Values(Layout::Random, Layout::Navmesh, Layout::Musse),
                                            ::testing::Values(std::size_t{1}, std::size_t{10}, std::size_t{400})),
                         [](const auto& info) {
                           return std::string(kLayoutNames[static_cast<int>(std::get<0>(info.param))]) + "_" +
                                  std::to_string(std::get<1>(info.param));
                         });

TEST(BenchScenarioNames, RoundTripAndRefuseOthers) {
  for (const Layout layout : {Layout::Random, Layout::Navmesh, Layout::Musse}) {
    EXPECT_EQ(layoutFromName(kLayoutNames[static_cast<int>(layout)]), layout);
  }
  EXPECT_FALSE(layoutFromName("mall").has_value());
  EXPECT_FALSE(layoutFromName("Random").has_value());
  EXPECT_FALSE(layoutFromName("").has_value());
}

TEST(BenchScenarioSquare, KeepsTheDensityAndAMinimumSide) {
  EXPECT_FLOAT_EQ(squareSide(10000), 100.0f);
  EXPECT_FLOAT_EQ(squareSide(400), 20.0f);
  EXPECT_FLOAT_EQ(squareSide(1), 2.0f);  // at least 2 m
  EXPECT_FLOAT_EQ(squareSide(0), 2.0f);
}

TEST(BenchStarts, AreOnTheNavmeshAndFollowTheSeed) {
  const sim::ScenarioDesc desc = makeScenario(Layout::Navmesh, 400, 1);
  auto navmesh = buildNavMesh(desc);
  ASSERT_TRUE(navmesh.ok());
  const auto starts = drawStarts(navmesh.value(), 300, 5);
  ASSERT_EQ(starts.size(), 300u);
  for (const core::Vec2 p : starts) {
    EXPECT_TRUE(p.x >= 0 && p.x <= 20 && p.y >= 0 && p.y <= 20) << p.x << ", " << p.y;
    EXPECT_FALSE(insidePillar(desc, p)) << p.x << ", " << p.y;
  }
  const auto again = drawStarts(navmesh.value(), 300, 5);
  const auto other = drawStarts(navmesh.value(), 300, 6);
  EXPECT_EQ(again[17].x, starts[17].x);
  EXPECT_EQ(again[17].y, starts[17].y);
  EXPECT_FALSE(other[17].x == starts[17].x && other[17].y == starts[17].y);
}

}  // namespace
}  // namespace throng::bench

// Tests for libs/bench/src/detour_crowd_baseline.cpp (throng::bench::runDetourCrowd): on a bench
// scenario's navmesh it runs a few ticks, agents move, progress is reported for every tick, and bad
// configs are diagnosed. No timing assertions.
#include "throng/bench/detour_crowd_baseline.hpp"

#include <gtest/gtest.h>

#include "throng/bench/scenarios.hpp"

namespace throng::bench {
namespace {

std::shared_ptr<const nav::NavMesh> benchMesh(Layout layout, std::size_t agents) {
  auto mesh = buildNavMesh(makeScenario(layout, agents, 1));
  EXPECT_TRUE(mesh.ok()) << (mesh.ok() ? "" : core::formatAll(mesh.errors()));
  return mesh.ok() ? mesh.value() : nullptr;
}

TEST(DetourCrowdBaseline, FiftyAgentsInARoomMove) {
  auto mesh = benchMesh(Layout::Random, 400);  // a 20 m square
  ASSERT_TRUE(mesh);
  BaselineConfig config;
  config.navmesh = mesh;
  for (int i = 0; i < 50; ++i) config.starts.push_back({1.0f + static_cast<float>(i % 10) * 2.0f, 1.0f + static_cast<float>(i / 10) * 2.0f});
  int calls = 0;
  config.progress = [&](int done, int total) {
    ++calls;
    EXPECT_EQ(done, calls);
    EXPECT_EQ(total, 45);
  };
  config.warmupTicks = 5;
  config.ticks = 40;
  auto result = runDetourCrowd(config);
  ASSERT_TRUE(result.ok()) << core::formatAll(result.errors());
  EXPECT_EQ(result->engine, "detourcrowd");
  EXPECT_EQ(result->agents, 50u);
  EXPECT_EQ(result->ticks, 40);
  EXPECT_GT(result->agentStepsPerSec, 0.0);
  EXPECT_GE(result->msPerTickP99, result->msPerTickMedian);
  EXPECT_GT(result->meanSpeed, 0.3 * config.speed);  // walking, not stuck
  EXPECT_LE(result->meanSpeed, config.speed * 1.01);
  EXPECT_EQ(calls, 45);
}

TEST(DetourCrowdBaseline, RunsOnTheBenchStartsAroundPillars) {
  auto mesh = benchMesh(Layout::Navmesh, 900);  // a 30 m square with 1 m pillars every 8 m
  ASSERT_TRUE(mesh);
  BaselineConfig config;
  config.navmesh = mesh;
  config.starts = drawStarts(mesh, 200, 3);
  config.warmupTicks = 2;
  config.ticks = 10;
  auto result = runDetourCrowd(config);
  ASSERT_TRUE(result.ok()) << core::formatAll(result.errors());
  EXPECT_EQ(result->agents, 200u);
  EXPECT_EQ(result->ticks, 10);
  EXPECT_GT(result->meanSpeed, 0.0);
}

TEST(DetourCrowdBaseline, RejectsBadConfig) {
  BaselineConfig config;
  config.ticks = 0;
  auto result = runDetourCrowd(config);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.errors().size(), 3u) << core::formatAll(result.errors());  // navmesh, starts, ticks

  auto mesh = benchMesh(Layout::Random, 400);
  ASSERT_TRUE(mesh);
  config = {};
  config.navmesh = mesh;
  config.starts.assign(kDetourCrowdMaxAgents + 1, core::Vec2{5, 5});
  auto tooMany = runDetourCrowd(config);
  ASSERT_FALSE(tooMany.ok());
  EXPECT_NE(tooMany.errors()[0].expected.find("16 bits"), std::string::npos);
}

}  // namespace
}  // namespace throng::bench

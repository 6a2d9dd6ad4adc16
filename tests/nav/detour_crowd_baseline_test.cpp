// Tests for throng::baselines::runDetourCrowd (benches/baselines/detour_crowd_baseline.cpp): it
// runs, agents move, and bad configs are diagnosed. No timing assertions.
#include "baselines/detour_crowd_baseline.hpp"

#include <gtest/gtest.h>

#include "nav_test_worlds.hpp"

namespace throng::baselines {
namespace {
using nav::testing::rect;

TEST(DetourCrowdBaseline, FiftyAgentsInARoomMove) {
  nav::NavMeshConfig cfg;
  cfg.agentRadius = 0.25f;
  auto mesh = nav::testing::buildOrFail({rect(0, 0, 20, 20)}, {}, cfg);
  ASSERT_TRUE(mesh);
  BaselineConfig config;
  config.navmesh = mesh;
  for (int i = 0; i < 50; ++i) config.starts.push_back({1.0f + static_cast<float>(i % 10) * 2.0f, 1.0f + static_cast<float>(i / 10) * 2.0f});
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
}

TEST(DetourCrowdBaseline, RejectsBadConfig) {
  BaselineConfig config;
  config.ticks = 0;
  auto result = runDetourCrowd(config);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.errors().size(), 3u) << core::formatAll(result.errors());  // navmesh, starts, ticks

  auto mesh = nav::testing::buildOrFail({rect(0, 0, 20, 20)}, {});
  ASSERT_TRUE(mesh);
  config = {};
  config.navmesh = mesh;
  config.starts.assign(kDetourCrowdMaxAgents + 1, core::Vec2{5, 5});
  auto tooMany = runDetourCrowd(config);
  ASSERT_FALSE(tooMany.ok());
  EXPECT_NE(tooMany.errors()[0].expected.find("16 bits"), std::string::npos);
}

}  // namespace
}  // namespace throng::baselines

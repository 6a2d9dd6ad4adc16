// Tests for libs/sim/src/demographics.cpp: speeds drawn from Weidmann's age table (RiMEA test 7's
// bands) stay inside the band of each agent's age and fill it, the movement-impaired share walks
// in its own band, draws are a pure function of (seed, id), and a population without a table
// draws exactly the clipped normal speed it always did; spawning gives agents these speeds, the
// same for 1 and 8 threads.
#include "demographics.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "throng/core/rng.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

PopulationDesc byAge(float ageMin, float ageMax, float impaired) {
  PopulationDesc p;
  p.demographics.table = SpeedTable::WeidmannAge;
  p.demographics.ageMin = ageMin;
  p.demographics.ageMax = ageMax;
  p.demographics.impaired = impaired;
  return p;
}

TEST(Demographics, WeidmannBandsAreRiMEA7s) {
  const auto bands = weidmannAgeBands();
  ASSERT_EQ(bands.size(), 3u);
  EXPECT_FLOAT_EQ(bands[0].speedMin, 0.58f);
  EXPECT_FLOAT_EQ(bands[0].speedMax, 1.61f);
  EXPECT_FLOAT_EQ(bands[1].ageMin, 30.0f);
  EXPECT_FLOAT_EQ(bands[1].speedMin, 1.41f);
  EXPECT_FLOAT_EQ(bands[1].speedMax, 1.54f);
  EXPECT_FLOAT_EQ(bands[2].ageMin, 50.0f);
  EXPECT_FLOAT_EQ(bands[2].speedMin, 0.68f);
  EXPECT_FLOAT_EQ(bands[2].speedMax, 1.41f);
}

TEST(Demographics, SpeedsFollowTheAgeTable) {
  const PopulationDesc pop = byAge(kMinAge, kMaxAge, 0.1f);
  const auto bands = weidmannAgeBands();
  struct Seen {
    int count = 0;
    float lo = 1e9f, hi = -1e9f;
  };
  Seen seen[4];  // the three age bands, then the impaired
  for (std::uint32_t id = 0; id < 4000; ++id) {
    const Walker w = drawWalker(pop, 42, id);
    ASSERT_GE(w.age, kMinAge);
    ASSERT_LE(w.age, kMaxAge);
    std::size_t k = 3;
    float lo = kImpairedSpeedMin, hi = kImpairedSpeedMax;
    if (!w.impaired) {
      k = static_cast<std::size_t>(std::find_if(bands.begin(), bands.end(), [&](const AgeSpeedBand& b) { return w.age < b.ageMax; }) -
                                   bands.begin());
      ASSERT_LT(k, 3u) << "age " << w.age;
      lo = bands[k].speedMin;
      hi = bands[k].speedMax;
    }
    ASSERT_GE(w.speed, lo) << "id " << id << " age " << w.age;
    ASSERT_LE(w.speed, hi) << "id " << id << " age " << w.age;
    seen[k].count++;
    seen[k].lo = std::min(seen[k].lo, w.speed);
    seen[k].hi = std::max(seen[k].hi, w.speed);
  }
  // Each band is used and filled (uniform within it); about a tenth are impaired.
  const float los[4] = {0.58f, 1.41f, 0.68f, kImpairedSpeedMin}, his[4] = {1.61f, 1.54f, 1.41f, kImpairedSpeedMax};
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE("band " + std::to_string(k));
    EXPECT_GT(seen[k].count, 200);
    EXPECT_NEAR(seen[k].lo, los[k], 0.03f * (his[k] - los[k]) + 0.01f);
    EXPECT_NEAR(seen[k].hi, his[k], 0.03f * (his[k] - los[k]) + 0.01f);
  }
  EXPECT_NEAR(seen[3].count / 4000.0, 0.1, 0.02);
}

TEST(Demographics, AgesStayInThePopulationsRange) {
  const PopulationDesc middle = byAge(32, 48, 0.0f);
  for (std::uint32_t id = 0; id < 500; ++id) {
    const Walker w = drawWalker(middle, 7, id);
    EXPECT_FALSE(w.impaired);
    EXPECT_GE(w.age, 32.0f);
    EXPECT_LE(w.age, 48.0f);
    EXPECT_GE(w.speed, 1.41f);  // everyone in the 30–50 band
    EXPECT_LE(w.speed, 1.54f);
  }
}

TEST(Demographics, DrawsArePerSeedAndId) {
  const PopulationDesc pop = byAge(kMinAge, kMaxAge, 0.2f);
  const Walker a = drawWalker(pop, 5, 17);
  const Walker b = drawWalker(pop, 5, 17);
  EXPECT_EQ(a.speed, b.speed);
  EXPECT_EQ(a.age, b.age);
  EXPECT_EQ(a.impaired, b.impaired);
  EXPECT_NE(drawWalker(pop, 5, 18).age, a.age);
  EXPECT_NE(drawWalker(pop, 6, 17).age, a.age);
}

TEST(Demographics, WithoutATableTheSpeedIsTheClippedNormalDraw) {
  PopulationDesc pop;
  pop.speedMean = 1.3f;
  pop.speedSd = 0.3f;
  pop.speedMin = 0.9f;
  pop.speedMax = 1.6f;
  for (std::uint32_t id = 0; id < 200; ++id) {
    core::Rng rng(9, id, core::RngPurpose::Speed);
    const double v = std::clamp(rng.normal(1.3f, 0.3f), 0.9, 1.6);
    const Walker w = drawWalker(pop, 9, id);
    EXPECT_EQ(w.speed, static_cast<float>(v));
    EXPECT_FALSE(w.impaired);
    EXPECT_EQ(w.age, 0.0f);
  }
}

/// The desired speed of every agent one tick after spawning 300 agents aged 50–80, a fifth impaired.
std::vector<float> spawnedSpeeds(int threads, PopulationDesc* popOut = nullptr) {
  ScenarioDesc d;
  d.seed = 21;
  d.dt = 0.1f;
  d.walkable = {{{0, 0}, {40, 0}, {40, 40}, {0, 40}}};
  PointDesc exit;
  exit.id = "exit";
  exit.kind = PointKind::Exit;
  exit.position = {39, 20};
  exit.radius = 0.8f;
  d.points = {exit};
  PopulationDesc pop = byAge(50, 80, 0.2f);
  pop.id = "elders";
  pop.groups = 300;
  pop.spawn.kind = SpawnKind::Polygon;
  pop.spawn.polygon = {{1, 1}, {30, 1}, {30, 39}, {1, 39}};
  pop.goals = {0};
  d.populations = {pop};
  if (popOut) *popOut = pop;
  auto created = World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  std::vector<float> speeds;
  if (!created.ok()) return speeds;
  core::TaskSystem tasks(threads);
  created.value()->step(tasks);
  for (std::uint32_t id = 0; id < 300; ++id) {
    const auto info = created.value()->agentInfo(id);
    speeds.push_back(info ? info->speed : -1.0f);
  }
  return speeds;
}

TEST(Demographics, SpawnedAgentsWalkAtTheirDraws) {
  PopulationDesc pop;
  const std::vector<float> one = spawnedSpeeds(1, &pop);
  ASSERT_EQ(one.size(), 300u);
  int impaired = 0;
  for (std::uint32_t id = 0; id < 300; ++id) {
    const Walker w = drawWalker(pop, 21, id);
    EXPECT_EQ(one[id], w.speed) << "agent " << id;
    EXPECT_LE(one[id], 1.41f);  // nobody over 50 walks faster than the band allows
    impaired += w.impaired;
  }
  EXPECT_GT(impaired, 30);
  EXPECT_EQ(spawnedSpeeds(8), one);
}

}  // namespace
}  // namespace throng::sim

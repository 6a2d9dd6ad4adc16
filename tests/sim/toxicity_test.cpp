// Tests for toxic smoke in libs/sim (decide.cpp's breathe and incapacitate; NIST TN 1822 test 2.6):
// in a region of 35 000 ppm carbon monoxide (a fractional effective dose of 1 a minute, ISO 13571)
// people standing there are incapacitated after 60 s (18 s for a population whose limit is 0.3),
// stop where they are and stay; people who walk out in time leave; the world ends when everyone is
// out or incapacitated; the same events for 1 and 4 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "throng/sim/world.hpp"

using namespace throng;

namespace {

/// A hall 30 × 4 m, its left 10 m full of smoke with `co` ppm; an exit at the right end. Three
/// populations of 4 start in the smoke (x 2..5): "late" and "sensitive" stand 90 s before walking
/// off, "early" walks off after 5 s; "sensitive" is incapacitated at a dose of 0.3.
sim::ScenarioDesc hall(float co) {
  sim::ScenarioDesc d;
  d.name = "toxic hall";
  d.seed = 3;
  d.duration = 200.0f;
  d.walkable = {{{0, 0}, {30, 0}, {30, 4}, {0, 4}}};
  sim::SmokeDesc smoke;
  smoke.polygon = {{0, 0}, {10, 0}, {10, 4}, {0, 4}};
  smoke.extinction = 0.5f;
  smoke.co = co;
  d.smoke = {smoke};
  sim::PointDesc exit;
  exit.id = "exit";
  exit.kind = sim::PointKind::Exit;
  exit.polygon = {{29, 0}, {30, 0}, {30, 4}, {29, 4}};
  exit.position = {29.5f, 2.0f};
  d.points = {exit};
  const auto population = [&](const char* id, float wait, float dose) {
    sim::PopulationDesc p;
    p.id = id;
    p.groups = 4;
    p.spawn.kind = sim::SpawnKind::Polygon;
    p.spawn.polygon = {{2, 0.5f}, {5, 0.5f}, {5, 3.5f}, {2, 3.5f}};
    p.goals = {0};
    p.speedMean = 1.34f;
    p.preMovement.distribution = sim::PreMovementDistribution::Uniform;
    p.preMovement.min = p.preMovement.max = wait;
    p.incapacitationDose = dose;
    p.model = sim::ModelDesc(sim::ModelKind::AnticipationVelocity);
    return p;
  };
  d.populations = {population("late", 90.0f, 1.0f), population("early", 5.0f, 1.0f), population("sensitive", 90.0f, 0.3f)};
  return d;
}

struct Incapacitation {
  double time = 0.0;        ///< when [s]
  std::uint32_t dose = 0;   ///< the event's FED × 1000
  float x = 0, y = 0;       ///< where
};

struct ToxicRun {
  std::map<std::uint32_t, Incapacitation> fallen;  ///< by agent id
  std::map<std::uint32_t, std::uint32_t> population;  ///< agent id → population index
  std::uint32_t exited = 0;
  float moved = 0.0f;  ///< the farthest an incapacitated agent moved after its event [m]
  double end = 0.0;    ///< when the world finished [s]
  bool finished = false;
};

ToxicRun run(const sim::ScenarioDesc& d, int threads) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  ToxicRun r;
  if (!created.ok()) return r;
  sim::World& w = *created.value();
  core::TaskSystem tasks(threads);
  tasks.setGrainLimit(2);
  while (!w.finished() && w.stats().time < d.duration) {
    w.step(tasks);
    const auto f = w.takeFrame();
    for (const sim::Event& e : f->events) {
      if (e.kind == sim::EventKind::Spawn) r.population[e.agent] = e.a;
      if (e.kind == sim::EventKind::Exit) ++r.exited;
      if (e.kind != sim::EventKind::Incapacitated) continue;
      for (std::size_t i = 0; i < f->size(); ++i) {
        if (f->ids[i] == e.agent) r.fallen[e.agent] = {static_cast<double>(e.tick) * d.dt, e.a, f->posX[i], f->posY[i]};
      }
    }
    for (std::size_t i = 0; i < f->size(); ++i) {
      const auto it = r.fallen.find(f->ids[i]);
      if (it == r.fallen.end()) continue;
      r.moved = std::max(r.moved, std::hypot(f->posX[i] - it->second.x, f->posY[i] - it->second.y));
    }
  }
  r.finished = w.finished();
  r.end = w.stats().time;
  return r;
}

TEST(Toxicity, PeopleInCarbonMonoxideAreIncapacitatedWhenTheirDoseReachesTheirLimitAndStay) {
  const sim::ScenarioDesc d = hall(35000.0f);  // FED 1 a minute
  const ToxicRun r = run(d, 1);
  ASSERT_EQ(r.fallen.size(), 8u) << "the 4 late and the 4 sensitive, not the 4 early";
  for (const auto& [id, f] : r.fallen) {
    const std::uint32_t pop = r.population.at(id);
    ASSERT_NE(pop, 1u) << "agent " << id << " walked out in time";
    const double expected = pop == 0 ? 60.0 : 18.0;  // dose / (1 per minute)
    EXPECT_NEAR(f.time, expected, 2.0 * d.dt) << "agent " << id;
    EXPECT_NEAR(f.dose, pop == 0 ? 1000u : 300u, 2u) << "agent " << id;
    EXPECT_LT(f.x, 10.0f) << "in the smoke";
  }
  EXPECT_LT(r.moved, 0.01f) << "an incapacitated person stays where it fell";
  EXPECT_EQ(r.exited, 4u) << "the early ones leave";
  EXPECT_TRUE(r.finished) << "everyone out or incapacitated: the world ends";
  EXPECT_LT(r.end, 90.0) << "before the late ones' pre-movement time is over";
}

TEST(Toxicity, CleanSmokeIncapacitatesNobodyAndLowCarbonMonoxideTakesLonger) {
  const ToxicRun clean = run(hall(0.0f), 1);
  EXPECT_TRUE(clean.fallen.empty());
  EXPECT_EQ(clean.exited, 12u);
  // 3 500 ppm: FED 1 after 10 minutes, the limit 0.3 after 3 minutes — later than everyone leaves.
  const ToxicRun low = run(hall(3500.0f), 1);
  EXPECT_TRUE(low.fallen.empty());
  EXPECT_EQ(low.exited, 12u);
}

TEST(Toxicity, TheSameIncapacitationsOnAnyThreadCount) {
  const sim::ScenarioDesc d = hall(35000.0f);
  const ToxicRun one = run(d, 1), four = run(d, 4);
  ASSERT_EQ(one.fallen.size(), four.fallen.size());
  for (const auto& [id, f] : one.fallen) {
    ASSERT_TRUE(four.fallen.count(id)) << id;
    EXPECT_EQ(four.fallen.at(id).time, f.time);
    EXPECT_EQ(four.fallen.at(id).x, f.x);
  }
}

}  // namespace

// Tests for stairs in libs/sim (steer.cpp's stair speed, plan.cpp's stair route costs, on the
// navmesh's stair area, nav::kStairArea): one walker up or down a staircase walks along the slope
// at its population's stair factor of its flat speed; a population whose stairs are slow enough
// takes a longer level detour instead; trajectories are identical for 1 and 8 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "terrain_quads.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

constexpr float kSpeed = 1.34f;  // [m/s]

using test::quad;

void level(nav::TerrainMesh& t, float x0, float y0, float x1, float y1, float z) {
  quad(t, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
}

/// Step tops from (x0, z0) up along x: `steps` treads `depth` deep, `rise` high, over y0..y1.
void stairs(nav::TerrainMesh& t, float x0, float y0, float y1, float z0, int steps, float depth, float rise) {
  for (int i = 0; i < steps; ++i) {
    const float x = x0 + static_cast<float>(i) * depth;
    level(t, x, y0, x + depth, y1, z0 + static_cast<float>(i + 1) * rise);
  }
}

// The staircase: 20 steps of 0.18 m on 0.3 m treads (31°, rise 0.6 per metre) from x 10 to 16.
constexpr float kRisePerMetre = 0.18f / 0.3f;

/// A corridor 2 m wide (y 0..2): level from x 0 to 10 at z 0, a staircase to x 16, level to x 26
/// at z 3.6 — or, `flat`, level all along at z 0.
nav::TerrainMesh corridor(bool flat) {
  nav::TerrainMesh t;
  if (flat) {
    level(t, 0, 0, 26, 2, 0);
    return t;
  }
  level(t, 0, 0, 10, 2, 0);
  stairs(t, 10, 0, 2, 0, 20, 0.3f, 0.18f);
  level(t, 16, 0, 26, 2, 3.6f);
  return t;
}

sim::PointDesc exitAt(std::string id, float x0, float x1, float y0, float y1, float height) {
  sim::PointDesc p;
  p.id = std::move(id);
  p.kind = sim::PointKind::Exit;
  p.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  p.position = {(x0 + x1) / 2, (y0 + y1) / 2};
  p.height = height;
  return p;
}

sim::PopulationDesc walkers(std::uint32_t n, core::Polygon spawn, float height, std::uint32_t goal) {
  sim::PopulationDesc p;
  p.id = "walkers";
  p.groups = n;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = std::move(spawn);
  p.spawn.height = height;
  p.goals = {goal};
  p.speedMean = kSpeed;
  return p;
}

/// One walker along the corridor, up (west to east) or down; its speed along the ground (3D) over
/// the middle of the staircase, x 11.5..14.5 (on the flat corridor: the same stretch).
struct Crossing {
  std::optional<double> enter, leave;  // [s]
  float enterX = 0, enterZ = 0, leaveX = 0, leaveZ = 0;
  [[nodiscard]] double speed() const {
    return std::hypot(leaveX - enterX, leaveZ - enterZ) / (*leave - *enter);
  }
};

double walkSpeed(bool flat, bool up, float stairUp = 0.53f, float stairDown = 0.60f) {
  sim::ScenarioDesc d;
  d.seed = 3;
  d.dt = 0.05f;
  d.terrain = corridor(flat);
  const float top = flat ? 0.0f : 3.6f;
  d.points = {exitAt("east", 24, 26, 0, 2, top), exitAt("west", 0, 2, 0, 2, 0.0f)};
  sim::PopulationDesc p = up ? walkers(1, {{2, 0.8f}, {2.4f, 0.8f}, {2.4f, 1.2f}, {2, 1.2f}}, 0.0f, 0)
                             : walkers(1, {{23.6f, 0.8f}, {24, 0.8f}, {24, 1.2f}, {23.6f, 1.2f}}, top, 1);
  p.stairUp = stairUp;
  p.stairDown = stairDown;
  d.populations = {p};
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  if (!created.ok()) return 0.0;
  sim::World& w = *created.value();
  core::TaskSystem tasks(1);
  Crossing c;
  const float from = up ? 11.5f : 14.5f, to = up ? 14.5f : 11.5f;
  while (!w.finished() && w.stats().time < 120.0 && !c.leave) {
    w.step(tasks);
    const auto f = w.takeFrame();
    if (f->size() != 1) continue;
    const float x = f->posX[0];
    const bool past = up ? x >= from : x <= from;
    const bool done = up ? x >= to : x <= to;
    if (past && !c.enter) c.enter = w.stats().time, c.enterX = x, c.enterZ = f->height(0);
    if (done && c.enter) c.leave = w.stats().time, c.leaveX = x, c.leaveZ = f->height(0);
  }
  EXPECT_TRUE(c.leave) << "the walker never crossed the staircase";
  return c.leave ? c.speed() : 0.0;
}

TEST(Stairs, WalkersClimbAndDescendAtTheirStairFactorAlongTheSlope) {
  const double flat = walkSpeed(true, true);
  EXPECT_NEAR(flat, kSpeed, 0.03 * kSpeed);
  const double up = walkSpeed(false, true);
  const double down = walkSpeed(false, false);
  EXPECT_NEAR(up / flat, 0.53, 0.03);
  EXPECT_NEAR(down / flat, 0.60, 0.03);
  // The factors of the population, not built-in numbers.
  const double slowUp = walkSpeed(false, true, 0.4f, 0.9f);
  const double fastDown = walkSpeed(false, false, 0.4f, 0.9f);
  EXPECT_NEAR(slowUp / flat, 0.4, 0.03);
  EXPECT_NEAR(fastDown / flat, 0.9, 0.04);
  // Factor 1: the flat speed along the slope, so less than it horizontally (cos 31°).
  const double free = walkSpeed(false, true, 1.0f, 1.0f);
  EXPECT_NEAR(free / flat, 1.0, 0.04);
  EXPECT_GT(kRisePerMetre, 0.5f);  // steeper than the 15° stair slope
}

/// A lower floor (z 0) and an upper one (z 2) joined two ways: a staircase (y 0..2: 8 steps of
/// 0.25 m on 0.3 m treads, 40°) and, 6 m further along y (y 6..8), a 12 m ramp (9.5°: level ground).
/// From the spawn to the exit the ramp is about 5.5 m longer.
sim::ScenarioDesc stairOrRamp(float stairFactor) {
  sim::ScenarioDesc d;
  d.seed = 9;
  d.dt = 0.1f;
  nav::TerrainMesh& t = d.terrain;
  level(t, 0, 0, 10, 8, 0);
  for (int i = 0; i < 8; ++i) level(t, 10 + 0.3f * i, 0, 10.3f + 0.3f * i, 2, 0.25f * (i + 1));
  level(t, 12.4f, 0, 22, 2, 2);
  quad(t, {{10, 6, 0}, {22, 6, 2}, {22, 8, 2}, {10, 8, 0}});
  level(t, 22, 0, 30, 8, 2);
  d.points = {exitAt("east", 27, 29, 0, 2, 2.0f)};
  sim::PopulationDesc p = walkers(6, {{3, 0.3f}, {7, 0.3f}, {7, 1.7f}, {3, 1.7f}}, 0.0f, 0);
  p.speedSd = 0.1f;
  p.stairUp = p.stairDown = stairFactor;
  d.populations = {p};
  return d;
}

struct RouteRun {
  float maxY = 0;  // the farthest any walker went from the staircase side (y 0..2)
  std::size_t exited = 0;
  std::uint64_t hash = 0;
};

RouteRun route(const sim::ScenarioDesc& d, int threads) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  RouteRun run;
  if (!created.ok()) return run;
  sim::World& w = *created.value();
  core::TaskSystem tasks(threads);
  while (!w.finished() && w.stats().time < 120.0) {
    w.step(tasks);
    const auto f = w.takeFrame();
    for (std::size_t i = 0; i < f->size(); ++i) run.maxY = std::max(run.maxY, f->posY[i]);
    for (const sim::Event& e : f->events) run.exited += e.kind == sim::EventKind::Exit;
    run.hash = run.hash * 1099511628211ull ^ w.stateHash();
  }
  return run;
}

TEST(Stairs, SlowStairsMakeWalkersTakeTheLevelDetour) {
  // Factor 0.2: a metre of stairs costs 5 level ones, the ~4 m of the stair area 20 m: the ramp.
  const RouteRun slow = route(stairOrRamp(0.2f), 1);
  EXPECT_EQ(slow.exited, 6u);
  EXPECT_GT(slow.maxY, 6.0f) << "took the ramp";
  // About the default factors (a metre of stairs costs 1.8): the stairs.
  const RouteRun usual = route(stairOrRamp(0.55f), 1);
  EXPECT_EQ(usual.exited, 6u);
  EXPECT_LT(usual.maxY, 3.0f) << "took the stairs";
}

TEST(Stairs, SameTrajectoriesFor1And8Threads) {
  sim::ScenarioDesc d = stairOrRamp(0.5f);
  d.populations[0].groups = 24;
  d.populations[0].spawn.polygon = {{1, 0.3f}, {9, 0.3f}, {9, 7.7f}, {1, 7.7f}};
  const RouteRun one = route(d, 1);
  const RouteRun eight = route(d, 8);
  EXPECT_EQ(one.hash, eight.hash);
  EXPECT_EQ(one.exited, 24u);
}

}  // namespace

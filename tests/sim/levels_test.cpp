// Tests for multi-level worlds in libs/sim (ScenarioDesc::terrain): agents climb a ramp to reach a
// goal on the floor above, agents on different floors are not neighbours, heights come out in
// frames, and trajectories stay identical for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "terrain_quads.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

using test::quad;

/// A ground floor (0..20 × 0..10 at z 0), an upper floor right above it (z 3) and, beside them
/// (y 10..12), a ramp from z 0 at x 2 to z 3 at x 18 with landings on each floor level: the only
/// way between the floors.
nav::TerrainMesh twoFloors() {
  nav::TerrainMesh t;
  quad(t, {{0, 0, 0}, {20, 0, 0}, {20, 10, 0}, {0, 10, 0}});
  quad(t, {{0, 0, 3}, {20, 0, 3}, {20, 10, 3}, {0, 10, 3}});
  quad(t, {{0, 10, 0}, {2, 10, 0}, {2, 12, 0}, {0, 12, 0}});      // lower landing (joins the ground floor)
  quad(t, {{2, 10, 0}, {18, 10, 3}, {18, 12, 3}, {2, 12, 0}});     // ramp, 10.6°
  quad(t, {{18, 10, 3}, {20, 10, 3}, {20, 12, 3}, {18, 12, 3}});   // upper landing (joins the upper floor)
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

sim::PopulationDesc walkers(std::string id, std::uint32_t n, core::Polygon spawn, float height, std::uint32_t goal) {
  sim::PopulationDesc p;
  p.id = std::move(id);
  p.groups = n;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = std::move(spawn);
  p.spawn.height = height;
  p.goals = {goal};
  p.radius = 0.2f;
  return p;
}

struct Track {
  float maxY = -1e9f, minZ = 1e9f, maxZ = -1e9f, lastZ = 0;
  float maxLateral = 0;  // largest |y - 5| (crossing test)
  bool exited = false;
};

struct LevelRun {
  std::map<std::uint32_t, Track> tracks;
  std::uint64_t hash = 0;
  double time = 0;
};

LevelRun simulate(const sim::ScenarioDesc& d, int threads, double maxTime) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  LevelRun run;
  if (!created.ok()) return run;
  sim::World& w = *created.value();
  core::TaskSystem tasks(threads);
  while (!w.finished() && w.stats().time < maxTime) {
    w.step(tasks);
    const auto f = w.takeFrame();
    EXPECT_EQ(f->posZ.size(), f->size());
    for (std::size_t i = 0; i < f->size(); ++i) {
      Track& t = run.tracks[f->ids[i]];
      t.maxY = std::max(t.maxY, f->posY[i]);
      t.minZ = std::min(t.minZ, f->height(i));
      t.maxZ = std::max(t.maxZ, f->height(i));
      t.lastZ = f->height(i);
      t.maxLateral = std::max(t.maxLateral, std::abs(f->posY[i] - 5.0f));
    }
    for (const sim::Event& e : f->events) {
      if (e.kind == sim::EventKind::Exit) run.tracks[e.agent].exited = true;
    }
    run.hash ^= w.stateHash() + 0x9e3779b97f4a7c15ull + (run.hash << 6) + (run.hash >> 2);
  }
  run.time = w.stats().time;
  return run;
}

TEST(Levels, AgentsClimbTheRampToAGoalRightAboveThem) {
  sim::ScenarioDesc d;
  d.name = "two floors";
  d.seed = 5;
  d.dt = 0.1f;
  d.terrain = twoFloors();
  // The goal is on the upper floor straight above the spawn: the way there is the ramp.
  d.points = {exitAt("top", 1, 5, 3, 7, 3.0f), exitAt("bottom", 15, 19, 3, 7, 0.0f)};
  d.populations = {walkers("up", 4, {{1, 3}, {5, 3}, {5, 7}, {1, 7}}, 0.0f, 0),
                   walkers("down", 4, {{15, 3}, {19, 3}, {19, 7}, {15, 7}}, 3.0f, 1)};
  const LevelRun run = simulate(d, 2, 120.0);
  ASSERT_EQ(run.tracks.size(), 8u);
  for (const auto& [id, t] : run.tracks) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_TRUE(t.exited);
    EXPECT_GT(t.maxY, 10.0f) << "went by the ramp (y 10..12)";
    EXPECT_LT(t.minZ, 0.2f);
    EXPECT_GT(t.maxZ, 2.8f);
  }
  // "up" agents (ids 0-3) end upstairs, "down" agents (4-7) downstairs.
  for (std::uint32_t id = 0; id < 4; ++id) EXPECT_NEAR(run.tracks.at(id).lastZ, 3.0f, 0.2f);
  for (std::uint32_t id = 4; id < 8; ++id) EXPECT_NEAR(run.tracks.at(id).lastZ, 0.0f, 0.2f);
}

/// Two agents head on along y = 5 in projection; the second walks on the floor at `secondFloor`.
LevelRun headOn(float secondFloor) {
  sim::ScenarioDesc d;
  d.seed = 7;
  d.dt = 0.1f;
  d.terrain = twoFloors();
  d.points = {exitAt("east", 18, 20, 4.9f, 5.1f, 0.0f), exitAt("west", 0, 2, 4.9f, 5.1f, secondFloor)};
  d.populations = {walkers("first", 1, {{2.5f, 4.9f}, {3.0f, 4.9f}, {3.0f, 5.1f}, {2.5f, 5.1f}}, 0.0f, 0),
                   walkers("second", 1, {{17.0f, 4.9f}, {17.5f, 4.9f}, {17.5f, 5.1f}, {17.0f, 5.1f}}, secondFloor, 1)};
  return simulate(d, 1, 60.0);
}

TEST(Levels, AgentsOnDifferentFloorsDoNotAvoidEachOther) {
  // One floor apart: each walks straight down the middle line.
  const LevelRun apart = headOn(3.0f);
  ASSERT_EQ(apart.tracks.size(), 2u);
  for (const auto& [id, t] : apart.tracks) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_TRUE(t.exited);
    EXPECT_LT(t.maxLateral, 0.15f) << "no sidestep for an agent on the other floor";
  }
  EXPECT_NEAR(apart.tracks.at(0).maxZ, 0.0f, 0.1f);
  EXPECT_NEAR(apart.tracks.at(1).minZ, 3.0f, 0.1f);
  // The control: on the same floor they do step aside for each other.
  const LevelRun together = headOn(0.0f);
  ASSERT_EQ(together.tracks.size(), 2u);
  EXPECT_GT(std::max(together.tracks.at(0).maxLateral, together.tracks.at(1).maxLateral), 0.2f);
}

TEST(Levels, SameTrajectoriesForAnyThreadCount) {
  sim::ScenarioDesc d;
  d.seed = 11;
  d.dt = 0.1f;
  d.terrain = twoFloors();
  d.points = {exitAt("top", 1, 5, 3, 7, 3.0f), exitAt("bottom", 15, 19, 3, 7, 0.0f)};
  d.populations = {walkers("up", 12, {{1, 1}, {8, 1}, {8, 9}, {1, 9}}, 0.0f, 0),
                   walkers("down", 12, {{12, 1}, {19, 1}, {19, 9}, {12, 9}}, 3.0f, 1)};
  const LevelRun one = simulate(d, 1, 30.0);
  const LevelRun two = simulate(d, 2, 30.0);
  EXPECT_EQ(one.hash, two.hash);
  EXPECT_EQ(one.tracks.size(), 24u);
}

TEST(Levels, AGuideOnTheUpperFloorLeadsItsGroupUpTheRamp) {
  // A group of four waits downstairs (its goal is where it stands); a guide (an avatar) stands on
  // the upper floor straight above it: the group must go round by the ramp and up to it.
  sim::ScenarioDesc d;
  d.seed = 3;
  d.dt = 0.1f;
  d.terrain = twoFloors();
  sim::PointDesc rest;
  rest.id = "rest";
  rest.position = {4, 5};
  rest.radius = 2.0f;
  d.points = {rest};
  sim::PopulationDesc p = walkers("class", 1, {{3, 4}, {5, 4}, {5, 6}, {3, 6}}, 0.0f, 0);
  p.sizeMin = p.sizeMax = 4;
  d.populations = {p};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  sim::World& w = *created.value();
  core::TaskSystem tasks(1);
  for (int i = 0; i < 20; ++i) w.step(tasks);
  ASSERT_TRUE(w.guide(w.groupById(0), {4, 5}, 3.0f));
  float lowest = 1e9f;
  float passedY = 0;
  for (int i = 0; i < 900; ++i) {
    w.step(tasks);
    const auto f = w.takeFrame();
    lowest = 1e9f;
    for (std::size_t k = 0; k < f->size(); ++k) {
      lowest = std::min(lowest, f->height(k));
      passedY = std::max(passedY, f->posY[k]);
    }
  }
  const auto f = w.takeFrame();
  ASSERT_EQ(f->size(), 4u);
  EXPECT_GT(passedY, 10.0f) << "they went by the ramp";
  EXPECT_GT(lowest, 2.8f) << "every member is upstairs with the guide";
  for (std::size_t k = 0; k < f->size(); ++k) {
    EXPECT_LT(std::hypot(f->posX[k] - 4.0f, f->posY[k] - 5.0f), 4.0f) << "near the guide: " << f->posX[k] << ", " << f->posY[k] << ", " << f->height(k);
  }
}

}  // namespace

/// Two avm walkers head on along y = 5 on the ground of a 20 × 10 m hall, with or without a gallery
/// 3 m above them (y 0 … 5.25, joined to nothing): its edge runs just north of their line.
LevelRun headOnUnderGallery(bool gallery) {
  sim::ScenarioDesc d;
  d.seed = 7;
  d.dt = 0.1f;
  quad(d.terrain, {{0, 0, 0}, {20, 0, 0}, {20, 10, 0}, {0, 10, 0}});
  if (gallery) quad(d.terrain, {{0, 0, 3}, {20, 0, 3}, {20, 5.25f, 3}, {0, 5.25f, 3}});
  d.points = {exitAt("east", 18, 20, 4.9f, 5.1f, 0.0f), exitAt("west", 0, 2, 4.9f, 5.1f, 0.0f)};
  d.populations = {walkers("first", 1, {{2.5f, 4.9f}, {3.0f, 4.9f}, {3.0f, 5.1f}, {2.5f, 5.1f}}, 0.0f, 0),
                   walkers("second", 1, {{17.0f, 4.9f}, {17.5f, 4.9f}, {17.5f, 5.1f}, {17.0f, 5.1f}}, 0.0f, 1)};
  return simulate(d, 1, 60.0);
}

TEST(Levels, AnotherFloorsEdgesAreNoWallsToWalkersBelow) {
  // The walker going west keeps right, north, out from under the gallery: its edge, 3 m up, must not
  // take the room to step aside (avm's room to pass, its look ahead, its slip), so both sidestep as
  // in the same hall without the gallery. Before, the edge was a wall to them.
  const LevelRun under = headOnUnderGallery(true);
  const LevelRun open = headOnUnderGallery(false);
  ASSERT_EQ(under.tracks.size(), 2u);
  ASSERT_EQ(open.tracks.size(), 2u);
  for (std::uint32_t id = 0; id < 2; ++id) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_TRUE(under.tracks.at(id).exited);
    EXPECT_GT(open.tracks.at(id).maxLateral, 0.1f) << "they do step aside for each other";
    EXPECT_NEAR(under.tracks.at(id).maxLateral, open.tracks.at(id).maxLateral, 0.02f);
  }
  EXPECT_NEAR(under.time, open.time, 0.3);
}

// A target drawn where the navmesh's erosion has no floor, on the upper floor of a multi-level
// world, is put 3 cm inside the mesh on that floor, not on its edge (as on flat worlds: goals.cpp
// kTargetInset; Goals.ATargetInTheNavmeshMarginLiesJustInsideTheMeshNotOnItsEdge). Red when the
// multi-level branch snaps to the nearest point only (the target then lies on the edge).
TEST(Levels, ATargetInTheNavmeshMarginOfAnUpperFloorLiesJustInsideTheMesh) {
  sim::ScenarioDesc d;
  d.seed = 3;
  d.dt = 0.1f;
  d.terrain = twoFloors();
  sim::PointDesc edge = exitAt("edge", 9.5f, 10.5f, 0.0f, 0.06f, 3.0f);  // wholly in the margin along y = 0
  edge.kind = sim::PointKind::Interest;
  d.points = {edge};
  d.populations = {walkers("upstairs", 1, {{9, 4}, {11, 4}, {11, 6}, {9, 6}}, 3.0f, 0)};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  sim::World& w = *created.value();
  core::TaskSystem tasks(1);
  w.step(tasks);
  const auto info = w.agentInfo(0);
  ASSERT_TRUE(info.has_value());
  EXPECT_NEAR(info->targetHeight, 3.0f, 0.05f) << "on the upper floor";
  const nav::NavQuery query(std::shared_ptr<const nav::NavMesh>(std::shared_ptr<const void>{}, &w.navMesh()));
  const core::Vec2 t = info->target;
  const auto on = query.snap(t, 3.0f, 0.1f);
  ASSERT_TRUE(on.has_value());
  EXPECT_LT(core::length(on->p - t), 1e-4f) << "the target is on the mesh: " << t.x << ", " << t.y;
  EXPECT_NEAR(on->height, 3.0f, 0.05f);
  const core::Vec2 nearer{t.x, t.y - 0.02f}, past{t.x, t.y - 0.05f};
  const auto below = query.snap(nearer, 3.0f, 0.1f);
  ASSERT_TRUE(below.has_value());
  EXPECT_LT(core::length(below->p - nearer), 1e-4f) << "2 cm nearer the wall is still floor";
  const auto edgeHit = query.snap(past, 3.0f, 0.1f);
  ASSERT_TRUE(edgeHit.has_value());
  EXPECT_GT(core::length(edgeHit->p - past), 1e-3f) << "5 cm nearer is past the edge";
}

// 90 people walk straight at a 3 m wide, 29° stair that runs up over the ground floor (4.5 m up,
// no railings) to an upper floor with their exit. Corners are followed in the plane: someone
// pushed off the stair's foot onto the ground beside it walked on the ground toward the points
// under the stair's top and the exit, on the wrong floor, until it was found stuck. Off its path's
// floor it now re-plans (decide.cpp checkFloor): all out in 63–65 s on seeds 1–3, against 93–96 s
// before (ORCA: 33–55 s). Red without the check (over 90 s).
TEST(Levels, PeoplePushedOffAStairOverTheGroundReplanFromTheFloorTheyAreOn) {
  nav::TerrainMesh t;
  quad(t, {{0, 0, 0}, {24, 0, 0}, {24, 10, 0}, {0, 10, 0}});
  quad(t, {{8, 4, 0}, {16, 4, 4.5f}, {16, 7, 4.5f}, {8, 7, 0}});
  quad(t, {{16, 0, 4.5f}, {24, 0, 4.5f}, {24, 10, 4.5f}, {16, 10, 4.5f}});
  sim::ScenarioDesc d;
  d.seed = 1;
  d.dt = 0.05f;
  d.terrain = t;
  d.points = {exitAt("up", 22, 24, 4, 6, 4.5f)};
  sim::PopulationDesc p = walkers("crowd", 90, {{0.5f, 3.5f}, {7.5f, 3.5f}, {7.5f, 7.5f}, {0.5f, 7.5f}}, 0.0f, 0);
  d.populations = {p};
  const LevelRun run = simulate(d, 2, 120.0);
  int out = 0;
  for (const auto& [id, track] : run.tracks) out += track.exited ? 1 : 0;
  EXPECT_EQ(out, 90);
  EXPECT_LT(run.time, 80.0) << "everyone up and out";
}

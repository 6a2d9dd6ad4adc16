// Spawning (spawn.cpp). In crowded areas: when random free spots run out, every agent still lands
// inside its spawn area, on the navmesh, with no two bodies overlapping and nobody at the world
// origin (the old fallback); populations spawning together in one area are laid out together;
// run-time crowd insertion shares the code; the layout is the same for any thread count.
// Pre-movement time (RiMEA test 5): agents are present and standing from the start, each leaves
// after its own drawn time (the same for any thread count), and stand as obstacles meanwhile.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "throng/core/geometry.hpp"
#include "terrain_quads.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

constexpr core::Vec2 kCentre{15.0f, 10.0f};
constexpr float kInner = 3.0f, kOuter = 5.0f;

/// A ring between radii 3 and 5 m around (15, 10), as one simple polygon (a 0.05 m slit joins the
/// two circles): about 50 m².
Polygon ring() {
  Polygon p;
  constexpr int kSides = 96;
  const double slit = 0.01;  // [rad]
  for (int i = 0; i <= kSides; ++i) {
    const double a = slit + (2.0 * std::numbers::pi - 2.0 * slit) * i / kSides;
    p.push_back({kCentre.x + kOuter * static_cast<float>(std::cos(a)), kCentre.y + kOuter * static_cast<float>(std::sin(a))});
  }
  for (int i = kSides; i >= 0; --i) {
    const double a = slit + (2.0 * std::numbers::pi - 2.0 * slit) * i / kSides;
    p.push_back({kCentre.x + kInner * static_cast<float>(std::cos(a)), kCentre.y + kInner * static_cast<float>(std::sin(a))});
  }
  return p;
}

PopulationDesc standing(const std::string& id, std::uint32_t groups, std::uint32_t size, float radius) {
  PopulationDesc pop;
  pop.id = id;
  pop.groups = groups;
  pop.sizeMin = pop.sizeMax = size;
  pop.spawn.kind = SpawnKind::Polygon;
  pop.spawn.polygon = ring();
  pop.radius = radius;
  return pop;  // no goals: everyone is done on arrival and stands where it spawned
}

/// A 30 m x 20 m hall whose corner is the origin, the ring in its middle.
ScenarioDesc hall(std::vector<PopulationDesc> populations) {
  ScenarioDesc d;
  d.seed = 5;
  d.duration = 60.0f;
  d.walkable = {{{0, 0}, {30, 0}, {30, 20}, {0, 20}}};
  d.populations = std::move(populations);
  return d;
}

/// Every agent of the frame is inside the ring (within 2 cm: positions snap to the navmesh), no
/// two bodies overlap, and none is near the origin.
void expectWellPlaced(const Frame& f, float radius, std::size_t expected) {
  ASSERT_EQ(f.size(), expected);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const core::Vec2 p{f.posX[i], f.posY[i]};
    const float r = core::length(p - kCentre);
    EXPECT_TRUE(r > kInner - 0.02f && r < kOuter + 0.02f) << "agent " << f.ids[i] << " at (" << p.x << ", " << p.y << ")";
    EXPECT_GT(core::length(p), 1.0f) << "agent " << f.ids[i] << " at the origin";
    for (std::size_t j = i + 1; j < f.size(); ++j) {
      const float d = core::length(p - core::Vec2{f.posX[j], f.posY[j]});
      EXPECT_GE(d, 2.0f * radius) << "agents " << f.ids[i] << " and " << f.ids[j] << " overlap (" << d << " m apart)";
    }
  }
}

TEST(Spawn, FourPerSquareMetreInARingAllInsideWithoutOverlap) {
  const Polygon area = ring();
  const double m2 = std::fabs(core::signedArea(area));
  const auto agents = static_cast<std::uint32_t>(std::floor(4.0 * m2));  // 4 /m², what check accepts at r = 0.2 m
  auto w = World::create(hall({standing("crowd", agents, 1, 0.2f)}));
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  w.value()->step(tasks);
  const auto f = w.value()->takeFrame();
  EXPECT_EQ(w.value()->stats().spawned, agents);
  expectWellPlaced(*f, 0.2f, agents);
}

TEST(Spawn, PopulationsSharingTheRingAreLaidOutTogether) {
  const Polygon area = ring();
  const double m2 = std::fabs(core::signedArea(area));
  const auto groups = static_cast<std::uint32_t>(std::floor(4.0 * m2 / 3.0));  // groups of 3, 4 /m² in all
  auto w = World::create(hall({standing("a", groups / 2, 3, 0.2f), standing("b", groups - groups / 2, 3, 0.2f)}));
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  w.value()->step(tasks);
  expectWellPlaced(*w.value()->takeFrame(), 0.2f, 3 * groups);
  // Group members stand together: each within 2 m of its group's first member.
  const auto f = w.value()->takeFrame();
  for (std::size_t i = 0; i < f->size(); ++i) {
    const std::size_t first = i - i % 3;
    EXPECT_LT(core::length(core::Vec2{f->posX[i] - f->posX[first], f->posY[i] - f->posY[first]}), 2.0f) << "agent " << f->ids[i];
  }
}

TEST(Spawn, InsertedCrowdInACrowdedRingIsPlacedInside) {
  ScenarioDesc d = hall({standing("early", 40, 1, 0.2f)});
  auto w = World::create(d);
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  w.value()->step(tasks);
  const Polygon area = ring();
  const auto more = static_cast<std::uint32_t>(std::floor(4.0 * std::fabs(core::signedArea(area)))) - 40;
  CrowdDesc c;
  c.id = "late";
  c.basePoints = 0;
  c.basePopulations = 1;
  c.populations = {standing("late", more, 1, 0.2f)};
  ASSERT_TRUE(w.value()->insertCrowd(c).ok());
  w.value()->step(tasks);
  expectWellPlaced(*w.value()->takeFrame(), 0.2f, 40 + more);
}

TEST(Spawn, ALaterWaveTheCrowdedRingCannotHoldStandsInItNotMetresAway) {
  // 3 /m² stand in the ring; a second population brings it to 5 /m² a second later, more than free
  // spots can hold. Those left over take the roomiest spots inside the ring (the bodies step apart
  // in the first ticks), not free spots of the hall metres away (up to 15 m before: people in the
  // validation's 5 /m² ring walked back to their first waypoint for seconds).
  const double m2 = std::fabs(core::signedArea(ring()));
  PopulationDesc later = standing("later", static_cast<std::uint32_t>(std::floor(2.0 * m2)), 1, 0.2f);
  later.start = 1.0f;
  auto w = World::create(hall({standing("first", static_cast<std::uint32_t>(std::floor(3.0 * m2)), 1, 0.2f), later}));
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  while (w.value()->stats().time < 1.1) w.value()->step(tasks);
  const auto f = w.value()->takeFrame();
  ASSERT_EQ(f->size(), static_cast<std::size_t>(std::floor(3.0 * m2) + std::floor(2.0 * m2)));
  int stacked = 0;
  for (std::size_t i = 0; i < f->size(); ++i) {
    const core::Vec2 p{f->posX[i], f->posY[i]};
    const float r = core::length(p - kCentre);
    EXPECT_TRUE(r > kInner - 0.05f && r < kOuter + 0.05f) << "agent " << f->ids[i] << " at (" << p.x << ", " << p.y << "), " << r << " m from the centre";
    for (std::size_t j = i + 1; j < f->size(); ++j) stacked += core::length(p - core::Vec2{f->posX[j], f->posY[j]}) < 0.1f ? 1 : 0;
  }
  EXPECT_EQ(stacked, 0) << "pairs of bodies less than 0.1 m apart: not the roomiest spots";
}

TEST(Spawn, CrowdedLayoutIsTheSameForAnyThreadCount) {
  const Polygon area = ring();
  const auto agents = static_cast<std::uint32_t>(std::floor(4.0 * std::fabs(core::signedArea(area))));
  ScenarioDesc d = hall({standing("crowd", agents, 1, 0.2f)});
  PointDesc exit;
  exit.id = "out";
  exit.kind = PointKind::Exit;
  exit.position = {28, 10};
  exit.radius = 1.0f;
  d.points = {exit};
  d.populations[0].goals = {0};
  std::uint64_t hash = 0;
  for (const int threads : {1, 2, 8}) {
    auto w = World::create(d);
    ASSERT_TRUE(w.ok());
    core::TaskSystem tasks(threads);
    for (int t = 0; t < 40; ++t) w.value()->step(tasks);
    if (threads == 1) hash = w.value()->stateHash();
    else EXPECT_EQ(w.value()->stateHash(), hash) << threads << " threads";
  }
}

using test::quad;

TEST(Spawn, CrowdedFloorsOfAMultiLevelWorldEachKeepTheirOwn) {
  // A ground floor and an upper floor 3 m above it, joined by a ramp; one crowd on each floor over
  // the same 4 m x 4 m square, each about 3.9 /m².
  ScenarioDesc d;
  d.seed = 9;
  d.duration = 10.0f;
  quad(d.terrain, {{0, 0, 0}, {20, 0, 0}, {20, 10, 0}, {0, 10, 0}});
  quad(d.terrain, {{0, 0, 3}, {20, 0, 3}, {20, 10, 3}, {0, 10, 3}});
  quad(d.terrain, {{0, 10, 0}, {2, 10, 0}, {2, 12, 0}, {0, 12, 0}});
  quad(d.terrain, {{2, 10, 0}, {18, 10, 3}, {18, 12, 3}, {2, 12, 0}});
  quad(d.terrain, {{18, 10, 3}, {20, 10, 3}, {20, 12, 3}, {18, 12, 3}});
  const Polygon square{{8, 3}, {12, 3}, {12, 7}, {8, 7}};
  for (const float height : {0.0f, 3.0f}) {
    PopulationDesc pop = standing(height == 0.0f ? "below" : "above", 62, 1, 0.2f);
    pop.spawn.polygon = square;
    pop.spawn.height = height;
    d.populations.push_back(pop);
  }
  auto w = World::create(d);
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  w.value()->step(tasks);
  const auto f = w.value()->takeFrame();
  ASSERT_EQ(f->size(), 124u);
  for (std::size_t i = 0; i < f->size(); ++i) {
    const float floor = f->ids[i] < 62 ? 0.0f : 3.0f;
    EXPECT_NEAR(f->height(i), floor, 0.05f) << "agent " << f->ids[i];
    EXPECT_TRUE(f->posX[i] > 7.98f && f->posX[i] < 12.02f && f->posY[i] > 2.98f && f->posY[i] < 7.02f)
        << "agent " << f->ids[i] << " at (" << f->posX[i] << ", " << f->posY[i] << ")";
    for (std::size_t j = i + 1; j < f->size(); ++j) {
      if ((f->ids[j] < 62) != (f->ids[i] < 62)) continue;  // other floor
      EXPECT_GE(core::length(core::Vec2{f->posX[i] - f->posX[j], f->posY[i] - f->posY[j]}), 0.4f)
          << "agents " << f->ids[i] << " and " << f->ids[j];
    }
  }
}

/// RiMEA test 5: ten persons in a room, each with a pre-movement time drawn uniformly from
/// 10-100 s, walking to the exit on the far side of a 20 m x 10 m room (dt 0.05 s).
ScenarioDesc rimeaFive() {
  ScenarioDesc d;
  d.seed = 7;
  d.dt = 0.05f;
  d.duration = 150.0f;
  d.walkable = {{{0, 0}, {20, 0}, {20, 10}, {0, 10}}};
  PointDesc exit;
  exit.id = "exit";
  exit.kind = PointKind::Exit;
  exit.position = {19, 5};
  exit.radius = 1.0f;
  d.points = {exit};
  PopulationDesc pop;
  pop.id = "persons";
  pop.groups = 10;
  pop.spawn.kind = SpawnKind::Polygon;
  pop.spawn.polygon = {{2, 2}, {8, 2}, {8, 8}, {2, 8}};
  pop.goals = {0};
  pop.preMovement.distribution = PreMovementDistribution::Uniform;
  pop.preMovement.min = 10.0f;
  pop.preMovement.max = 100.0f;
  d.populations = {pop};
  return d;
}

/// When each agent (by stable id) left: the time of the first frame in which it is no longer
/// waiting out its pre-movement time (-1: not within `until`). Fails the test when an agent is
/// missing from a frame before it left, or walks off (more than 0.5 m from where it appeared:
/// others passing by may nudge it) before it left.
std::vector<double> departures(const ScenarioDesc& d, int threads, double until) {
  auto created = World::create(d);
  EXPECT_TRUE(created.ok()) << core::formatAll(created.errors());
  if (!created.ok()) return {};
  World& w = *created.value();
  core::TaskSystem tasks(threads);
  tasks.setGrainLimit(1);  // every phase cut into chunks of one agent
  const FramePtr first = w.takeFrame();
  const std::size_t n = first->size();
  std::vector<double> leave(n, -1.0);
  std::vector<core::Vec2> start(n);
  for (std::size_t i = 0; i < n; ++i) start[first->ids[i]] = {first->posX[i], first->posY[i]};
  const std::string waiting = "waiting to leave (pre-movement time)";
  while (w.stats().time < until) {
    w.step(tasks);
    const FramePtr f = w.takeFrame();
    std::size_t stillWaiting = 0, present = 0;
    for (const double t : leave) stillWaiting += t < 0.0 ? 1 : 0;
    for (std::size_t i = 0; i < f->size(); ++i) {
      const std::uint32_t id = f->ids[i];
      if (leave[id] >= 0.0) continue;
      ++present;
      const auto info = w.agentInfo(id);
      if (!info || info->state != waiting) {
        leave[id] = f->time;
        continue;
      }
      EXPECT_LT(core::length(core::Vec2{f->posX[i], f->posY[i]} - start[id]), 0.5f) << "agent " << id << " walked off at " << f->time << " s";
    }
    EXPECT_EQ(present, stillWaiting) << "every agent that has not left is present at " << f->time << " s";
  }
  return leave;
}

TEST(Spawn, PreMovementUniform10To100sEveryAgentLeavesInsideTheIntervalAndNotBefore) {
  const ScenarioDesc d = rimeaFive();
  auto w = World::create(d);
  ASSERT_TRUE(w.ok());
  const FramePtr first = w.value()->takeFrame();
  ASSERT_EQ(first->size(), 10u) << "all ten are present from the start";
  const std::vector<double> leave = departures(d, 1, 110.0);
  ASSERT_EQ(leave.size(), 10u);
  double earliest = 1e9, latest = -1.0;
  for (std::size_t id = 0; id < leave.size(); ++id) {
    // The frame after the tick it moves off: within two ticks after its drawn time.
    EXPECT_GE(leave[id], 10.0) << "agent " << id << " left before its pre-movement time";
    EXPECT_LE(leave[id], 100.0 + 2 * d.dt) << "agent " << id;
    earliest = std::min(earliest, leave[id]);
    latest = std::max(latest, leave[id]);
  }
  EXPECT_GT(latest - earliest, 30.0) << "times are drawn per agent, not shared";
}

TEST(Spawn, PreMovementDrawsAreTheSameForOneAndEightThreads) {
  const ScenarioDesc d = rimeaFive();
  const std::vector<double> one = departures(d, 1, 105.0);
  const std::vector<double> eight = departures(d, 8, 105.0);
  ASSERT_EQ(one.size(), 10u);
  EXPECT_GE(*std::min_element(one.begin(), one.end()), 10.0) << "everyone waited";
  EXPECT_EQ(one, eight);
}

TEST(Spawn, AnAgentWaitingToLeaveIsAnObstacleOthersWalkAround) {
  // A walker heads east along y = 5 through where a person stands waiting (pre-movement 1000 s).
  ScenarioDesc d = rimeaFive();
  d.populations[0].groups = 1;
  d.populations[0].spawn.kind = SpawnKind::Position;
  d.populations[0].spawn.position = {10, 5};
  d.populations[0].preMovement.min = d.populations[0].preMovement.max = 1000.0f;
  PopulationDesc walker = d.populations[0];
  walker.id = "walker";
  walker.spawn.position = {3, 5};
  walker.preMovement = {};
  d.populations.push_back(walker);
  auto w = World::create(d);
  ASSERT_TRUE(w.ok()) << core::formatAll(w.errors());
  core::TaskSystem tasks(1);
  float closest = 1e9f, walkerX = 0.0f, drift = 0.0f;
  while (w.value()->stats().time < 20.0 && walkerX < 14.0f) {
    w.value()->step(tasks);
    const FramePtr f = w.value()->takeFrame();
    ASSERT_EQ(f->size(), 2u);
    const core::Vec2 waiting{f->posX[0], f->posY[0]}, walking{f->posX[1], f->posY[1]};
    closest = std::min(closest, core::length(waiting - walking));
    walkerX = walking.x;
    drift = std::max(drift, core::length(waiting - core::Vec2{10, 5}));
  }
  EXPECT_GE(walkerX, 14.0f) << "the walker got past";
  EXPECT_GE(closest, 0.38f) << "the bodies (r = 0.2 m) never overlapped";
  // ORCA shares avoidance between the two: the person standing steps aside, and stays standing.
  EXPECT_LT(drift, 1.5f) << "the waiting person was not carried along";
  EXPECT_EQ(w.value()->agentInfo(0)->state, "waiting to leave (pre-movement time)");
}

}  // namespace
}  // namespace throng::sim

// Tests for lifts and escalators (ScenarioDesc::transports, libs/sim/src/vertical_transport.cpp): people
// who reach a transport's boarding stop queue, are carried to the other stop in the times its
// parameters give, to the tick, and go on to their next goal; two floors joined by nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "terrain_quads.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

using test::quad;
using test::region;

/// Two 12 × 10 m floors, z 0 and z 4, joined by nothing walkable. Points: 0 "low" stop (ground,
/// x 0.5–2), 1 "high" stop (upper floor; over "low" for a lift, at the far end for an escalator),
/// 2 the exit on the ground floor (x 10.5–12), 3 the exit on the upper floor (x 10.5–12).
sim::ScenarioDesc twoFloors(bool escalator) {
  sim::ScenarioDesc d;
  d.name = escalator ? "escalator" : "lift";
  d.seed = 3;
  d.duration = 400;
  quad(d.terrain, {{0, 0, 0}, {12, 0, 0}, {12, 10, 0}, {0, 10, 0}});
  quad(d.terrain, {{0, 0, 4}, {12, 0, 4}, {12, 10, 4}, {0, 10, 4}});
  d.points.push_back(region("low", sim::PointKind::Interest, 0.5f, 2.0f, 4.0f, 6.0f, 0.0f));
  if (escalator) {
    d.points.push_back(region("high", sim::PointKind::Interest, 7.5f, 9.0f, 4.0f, 6.0f, 4.0f));
  } else {
    d.points.push_back(region("high", sim::PointKind::Interest, 0.5f, 2.0f, 4.0f, 6.0f, 4.0f));
  }
  d.points.push_back(region("exit-low", sim::PointKind::Exit, 10.5f, 12.0f, 3.0f, 7.0f, 0.0f));
  d.points.push_back(region("exit-high", sim::PointKind::Exit, 10.5f, 12.0f, 3.0f, 7.0f, 4.0f));
  sim::TransportDesc t;
  t.id = escalator ? "escalator" : "lift";
  t.kind = escalator ? sim::TransportKind::Escalator : sim::TransportKind::Elevator;
  t.stops[0] = 0;
  t.stops[1] = 1;
  t.speed = escalator ? 0.5f : 1.0f;
  d.transports.push_back(t);
  sim::PopulationDesc p;
  p.id = "people";
  p.groups = escalator ? 15 : 28;
  p.radius = 0.2f;
  p.spawn.kind = sim::SpawnKind::Polygon;
  if (escalator) {  // on the ground floor, up the escalator, out on the upper floor
    p.spawn.polygon = {{3, 2}, {7, 2}, {7, 8}, {3, 8}};
    p.spawn.height = 0.0f;
    p.goals = {0, 3};
  } else {  // on the upper floor, down by lift, out on the ground floor
    p.spawn.polygon = {{3, 1}, {9, 1}, {9, 9}, {3, 9}};
    p.spawn.height = 4.0f;
    p.goals = {1, 2};
  }
  d.populations.push_back(p);
  return d;
}

struct Ride {
  std::uint64_t board = 0;   ///< the last tick at the boarding stop's height before leaving it
  std::uint64_t alight = 0;  ///< the tick of the GoalReached at the other stop
  float minZ = 1e9f, maxZ = -1e9f;
  bool monotone = true;
  float lastZ = 0.0f;
  bool seen = false;
  bool exited = false;
};

struct RideRun {
  std::map<std::uint32_t, Ride> rides;
  std::uint64_t hash = 0;
};

RideRun simulate(const sim::ScenarioDesc& d, int threads, float startZ, float endZ, std::uint32_t arrivalPoint) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  RideRun run;
  if (!created.ok()) return run;
  sim::World& w = *created.value();
  core::TaskSystem tasks(threads);
  std::uint64_t tick = 0;
  while (!w.finished() && w.stats().time < d.duration) {
    w.step(tasks);
    ++tick;
    const auto f = w.takeFrame();
    for (std::size_t i = 0; i < f->size(); ++i) {
      Ride& r = run.rides[f->ids[i]];
      const float z = f->height(i);
      if (r.seen && (endZ > startZ ? z < r.lastZ - 1e-4f : z > r.lastZ + 1e-4f)) r.monotone = false;
      if (std::abs(z - startZ) < 1e-3f) r.board = tick;
      r.minZ = std::min(r.minZ, z);
      r.maxZ = std::max(r.maxZ, z);
      r.lastZ = z;
      r.seen = true;
    }
    for (const sim::Event& e : f->events) {
      if (e.kind == sim::EventKind::GoalReached && e.a == arrivalPoint) run.rides[e.agent].alight = tick;  // this step's
      if (e.kind == sim::EventKind::Exit) run.rides[e.agent].exited = true;
    }
  }
  run.hash = w.stateHash();
  return run;
}

std::uint64_t ticks(float seconds) { return static_cast<std::uint64_t>(std::lround(seconds / 0.05f)); }

}  // namespace

// An escalator from the ground floor to the upper one, 7 m across and 4 m up (8.06 m) at 0.5 m/s:
// everyone rides it, each for 8.06 / 0.5 s to the tick, stepping on at least a headway (0.8 s)
// after the one before, exactly a headway while a queue waits; they rise steadily, and then
// leave by the upper floor's exit.
TEST(VerticalTransport, EscalatorRidesTakeLengthOverSpeedAndBoardAHeadwayApart) {
  const sim::ScenarioDesc d = twoFloors(true);
  const RideRun run = simulate(d, 1, 0.0f, 4.0f, 1);
  ASSERT_EQ(run.rides.size(), 15u);
  const float length = std::sqrt(7.0f * 7.0f + 4.0f * 4.0f);
  std::vector<std::uint64_t> boards;
  for (const auto& [id, r] : run.rides) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_TRUE(r.exited) << "out by the upper floor's exit";
    ASSERT_GT(r.alight, 0u) << "reached the top stop";
    EXPECT_EQ(r.alight - r.board, ticks(length / 0.5f)) << "ride time in ticks";
    EXPECT_TRUE(r.monotone) << "rises steadily";
    EXPECT_NEAR(r.maxZ, 4.0f, 0.05f);
    boards.push_back(r.board);
  }
  std::sort(boards.begin(), boards.end());
  std::uint64_t closest = UINT64_MAX;
  for (std::size_t i = 1; i < boards.size(); ++i) closest = std::min(closest, boards[i] - boards[i - 1]);
  EXPECT_EQ(closest, ticks(0.8f)) << "one person every headway while the queue waits, never closer";
}

// A lift between the two floors (4 m, 1 m/s, 1 m/s², 8 people, doors 2 s / 3 s, transfer 1.2 s):
// 28 people on the upper floor go down in batches of at most 8. Once everyone waits, one batch's
// first arrival follows the last batch's by exactly what the rules add up to: the last batch
// alighting (k × 1.2 s), doors closing, the trip up (4 / 1 + 1 / 1 s), doors opening, the next k
// boarding, doors closing, the trip down, doors opening. And the lift is the only way down.
TEST(VerticalTransport, LiftCarriesBatchesInTheTimesItsRulesGive) {
  const sim::ScenarioDesc d = twoFloors(false);
  const RideRun run = simulate(d, 1, 4.0f, 0.0f, 0);
  ASSERT_EQ(run.rides.size(), 28u);
  std::map<std::uint64_t, int> perTick;
  std::vector<std::uint64_t> alights;
  for (const auto& [id, r] : run.rides) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_TRUE(r.exited) << "out by the ground floor's exit";
    ASSERT_GT(r.alight, 0u) << "reached the ground stop";
    EXPECT_TRUE(r.monotone) << "goes down only";
    alights.push_back(r.alight);
  }
  std::sort(alights.begin(), alights.end());
  // Batches: alights one transfer apart belong together.
  std::vector<std::vector<std::uint64_t>> batches{{alights[0]}};
  for (std::size_t i = 1; i < alights.size(); ++i) {
    if (alights[i] - alights[i - 1] == ticks(1.2f)) {
      batches.back().push_back(alights[i]);
    } else {
      batches.push_back({alights[i]});
    }
  }
  ASSERT_GE(batches.size(), 4u);
  for (const auto& b : batches) EXPECT_LE(b.size(), 8u) << "the car's capacity";
  const std::uint64_t trip = ticks(4.0f / 1.0f + 1.0f / 1.0f);
  for (std::size_t i = 2; i < batches.size(); ++i) {  // from the third batch on, everyone is waiting
    SCOPED_TRACE("batch " + std::to_string(i));
    const std::uint64_t expected = batches[i - 1].size() * ticks(1.2f) + ticks(3.0f) + trip + ticks(2.0f) +
                                   batches[i].size() * ticks(1.2f) + ticks(3.0f) + trip + ticks(2.0f);
    EXPECT_EQ(batches[i].front() - batches[i - 1].front(), expected);
  }
}

// The same lift run on 1 and 4 threads gives the same world.
TEST(VerticalTransport, LiftAndEscalatorRunsAreTheSameOnAnyThreadCount) {
  for (const bool escalator : {false, true}) {
    SCOPED_TRACE(escalator ? "escalator" : "lift");
    const sim::ScenarioDesc d = twoFloors(escalator);
    const RideRun one = simulate(d, 1, escalator ? 0.0f : 4.0f, escalator ? 4.0f : 0.0f, escalator ? 1 : 0);
    const RideRun four = simulate(d, 4, escalator ? 0.0f : 4.0f, escalator ? 4.0f : 0.0f, escalator ? 1 : 0);
    EXPECT_EQ(one.hash, four.hash);
  }
}

// Stops must be two different points, each of one transport only.
TEST(VerticalTransport, StopsThatAreNotTwoPointsAreRefused) {
  sim::ScenarioDesc d = twoFloors(true);
  d.transports[0].stops[1] = 0;
  auto same = sim::World::create(d);
  ASSERT_FALSE(same.ok());
  EXPECT_NE(core::formatAll(same.errors()).find("/transports/0/stops"), std::string::npos);
  d = twoFloors(true);
  d.transports[0].stops[1] = 9;
  EXPECT_FALSE(sim::World::create(d).ok());
  d = twoFloors(true);
  d.transports.push_back(d.transports[0]);
  d.transports[1].stops[0] = 2;
  auto shared = sim::World::create(d);
  ASSERT_FALSE(shared.ok());
  EXPECT_NE(core::formatAll(shared.errors()).find("another transport"), std::string::npos);
}

// A lift serving three floors (z 0, 4, 8): ten people on the top floor ride down to the ground
// floor's exit, ten on the middle floor up to the top floor's; each is let off only at the floor of
// its next goal, rides one way only (a landing's up and down buttons: nobody rides down to come up),
// and everybody leaves. The same on 1 and 4 threads.
TEST(VerticalTransport, ALiftServesThreeFloorsEachRiderOneWayToTheFloorOfItsNextGoal) {
  sim::ScenarioDesc d;
  d.name = "three floors";
  d.seed = 5;
  d.duration = 400;
  const float floors[3] = {0.0f, 4.0f, 8.0f};
  for (const float z : floors) quad(d.terrain, {{0, 0, z}, {12, 0, z}, {12, 10, z}, {0, 10, z}});
  sim::TransportDesc lift;
  lift.id = "lift";
  lift.kind = sim::TransportKind::Elevator;
  lift.speed = 1.0f;
  lift.stops.clear();
  for (int f = 0; f < 3; ++f) {
    lift.stops.push_back(static_cast<std::uint32_t>(d.points.size()));
    d.points.push_back(region("lift-" + std::to_string(f), sim::PointKind::Interest, 0.5f, 3.0f, 2.0f, 8.0f, floors[f]));
  }
  d.points.push_back(region("exit-0", sim::PointKind::Exit, 10.5f, 12.0f, 3.0f, 7.0f, 0.0f));  // 3
  d.points.push_back(region("exit-2", sim::PointKind::Exit, 10.5f, 12.0f, 3.0f, 7.0f, 8.0f));  // 4
  d.transports.push_back(lift);
  sim::PopulationDesc down;
  down.id = "down";
  down.groups = 10;
  down.radius = 0.2f;
  down.spawn.kind = sim::SpawnKind::Polygon;
  down.spawn.polygon = {{4, 1}, {9, 1}, {9, 9}, {4, 9}};
  down.spawn.height = 8.0f;
  down.goals = {2, 3};
  sim::PopulationDesc up = down;
  up.id = "up";
  up.spawn.height = 4.0f;
  up.goals = {1, 4};
  d.populations = {down, up};
  std::uint64_t hashes[2] = {0, 0};
  for (const int threads : {1, 4}) {
    auto created = sim::World::create(d);
    ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
    sim::World& w = *created.value();
    core::TaskSystem tasks(threads);
    std::map<std::uint32_t, std::vector<std::uint32_t>> stopsReached;  // id -> lift stops, in order
    std::map<std::uint32_t, float> firstZ, lastZ;
    std::map<std::uint32_t, bool> oneWay;
    std::size_t exited = 0;
    while (!w.finished() && w.stats().time < d.duration) {
      w.step(tasks);
      const auto f = w.takeFrame();
      for (std::size_t i = 0; i < f->size(); ++i) {
        const std::uint32_t id = f->ids[i];
        const float z = f->height(i);
        if (!firstZ.count(id)) firstZ[id] = z, oneWay[id] = true;
        const bool goingUp = firstZ[id] < 6.0f && firstZ[id] > 2.0f;  // the middle floor's people
        if (lastZ.count(id) && (goingUp ? z < lastZ[id] - 1e-4f : z > lastZ[id] + 1e-4f)) oneWay[id] = false;
        lastZ[id] = z;
      }
      for (const sim::Event& e : f->events) {
        if (e.kind == sim::EventKind::GoalReached && e.a <= 2) stopsReached[e.agent].push_back(e.a);
        if (e.kind == sim::EventKind::Exit) ++exited;
      }
    }
    SCOPED_TRACE(std::to_string(threads) + " threads");
    EXPECT_EQ(exited, 20u);
    ASSERT_EQ(stopsReached.size(), 20u);
    for (const auto& [id, stops] : stopsReached) {
      SCOPED_TRACE("agent " + std::to_string(id));
      const bool goingUp = firstZ[id] < 6.0f;
      EXPECT_EQ(stops, goingUp ? (std::vector<std::uint32_t>{1, 2}) : (std::vector<std::uint32_t>{2, 0}))
          << "boarded at its floor, let off only at its next goal's";
      EXPECT_TRUE(oneWay[id]) << "rode one way";
    }
    hashes[threads == 1 ? 0 : 1] = w.stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

// Groups ride a lift together: six groups of three come down by a lift for four. Those who come
// first wait for the rest of their group, a group that does not fit waits for the next car, and
// one of a group aboard brings the others next: each group's three step off within one stop's
// transfers (without these rules two groups were split over cars 33 and 60 s apart).
TEST(VerticalTransport, GroupsRideTogether) {
  sim::ScenarioDesc d = twoFloors(false);
  d.populations[0].groups = 6;
  d.populations[0].sizeMin = d.populations[0].sizeMax = 3;
  d.transports[0].capacity = 4;
  const RideRun run = simulate(d, 1, 4.0f, 0.0f, 0);
  ASSERT_EQ(run.rides.size(), 18u);
  // Ids are given group by group: 3k, 3k + 1, 3k + 2 form group k.
  for (std::uint32_t g = 0; g < 6; ++g) {
    std::uint64_t first = UINT64_MAX, last = 0;
    for (std::uint32_t id = 3 * g; id < 3 * g + 3; ++id) {
      const Ride& r = run.rides.at(id);
      ASSERT_GT(r.alight, 0u) << "agent " << id;
      first = std::min(first, r.alight);
      last = std::max(last, r.alight);
    }
    EXPECT_LE(last - first, ticks(3 * 1.2f)) << "group " << g << " stepped off over " << (last - first) * 0.05 << " s";
  }
}

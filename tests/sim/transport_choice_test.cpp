// Tests for choosing a lift, an escalator or the stairs (PopulationDesc::useTransports,
// libs/sim/src/transport_choice.cpp): people whose goal is on another floor ride when that is
// quicker than walking, counting the queue they would join, and walk otherwise; the same on any
// thread count.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "terrain_quads.hpp"
#include "timeline.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

using test::quad;
using test::region;

sim::TransportDesc transport(std::string id, sim::TransportKind kind, std::uint32_t from, std::uint32_t to, float speed) {
  sim::TransportDesc t;
  t.id = std::move(id);
  t.kind = kind;
  t.stops = {from, to};
  t.speed = speed;
  return t;
}

/// A split-level world: a 12 × 10 m ground floor (z 0), a 3 m wide stair up the side (x 12–20, 26.6°)
/// and a 12 × 10 m upper floor beyond it (x 20–32, z 4). Points: 0 the escalator's foot (ground,
/// x 9–11), 1 its head (upper floor, x 21–23), 2 the exit at the upper floor's far end. Population:
/// `people` on the ground floor (x 2–6) whose only goal is the exit; no goal names a stop. Every
/// group weighs the stairs by time (stairs.climb 1 each way) unless `climb` says otherwise.
sim::ScenarioDesc splitLevel(float escalatorSpeed, std::uint32_t people, bool stairs = true, float climb = 1.0f) {
  sim::ScenarioDesc d;
  d.name = "split level";
  d.seed = 5;
  d.duration = 300;
  quad(d.terrain, {{0, 0, 0}, {12, 0, 0}, {12, 10, 0}, {0, 10, 0}});
  if (stairs) quad(d.terrain, {{12, 0, 0}, {20, 0, 4}, {20, 3, 4}, {12, 3, 0}});
  quad(d.terrain, {{20, 0, 4}, {32, 0, 4}, {32, 10, 4}, {20, 10, 4}});
  d.points.push_back(region("foot", sim::PointKind::Interest, 9.0f, 11.0f, 6.0f, 8.0f, 0.0f));
  d.points.push_back(region("head", sim::PointKind::Interest, 21.0f, 23.0f, 6.0f, 8.0f, 4.0f));
  d.points.push_back(region("exit", sim::PointKind::Exit, 30.5f, 32.0f, 3.0f, 7.0f, 4.0f));
  d.transports.push_back(transport("escalator", sim::TransportKind::Escalator, 0, 1, escalatorSpeed));
  sim::PopulationDesc p;
  p.id = "people";
  p.groups = people;
  p.radius = 0.2f;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = {{2, 3}, {6, 3}, {6, 7}, {2, 7}};
  p.goals = {2};
  p.stairClimbUp = p.stairClimbDown = climb;
  d.populations.push_back(p);
  return d;
}

struct Outcome {
  std::map<std::uint32_t, std::uint32_t> boardings;  ///< boarding stop point → groups that chose it
  std::uint32_t exited = 0;
  double lastExit = 0.0;
  std::uint64_t hash = 0;
};

Outcome simulate(const sim::ScenarioDesc& d, int threads = 1) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  Outcome out;
  if (!created.ok()) return out;
  sim::World& w = *created.value();
  core::TaskSystem tasks(threads);
  while (!w.finished() && w.stats().time < d.duration) {
    w.step(tasks);
    const auto f = w.takeFrame();
    for (const sim::Event& e : f->events) {
      if (e.kind == sim::EventKind::WaypointChosen) ++out.boardings[e.a];
      if (e.kind == sim::EventKind::Exit) {
        ++out.exited;
        out.lastExit = w.stats().time;
      }
    }
  }
  out.hash = w.stateHash();
  return out;
}

}  // namespace

// Only an escalator joins the floors: everyone rides it of their own accord and leaves upstairs;
// with useTransports off nobody finds a way up.
TEST(TransportChoice, PeopleRideTheOnlyWayToAnotherFloor) {
  sim::ScenarioDesc d = splitLevel(0.5f, 12, false);
  const Outcome ride = simulate(d);
  EXPECT_EQ(ride.boardings.size(), 1u);
  EXPECT_EQ(ride.boardings.count(0), 1u);
  EXPECT_EQ(ride.boardings.at(0), 12u);
  EXPECT_EQ(ride.exited, 12u);
  d.populations[0].useTransports = false;
  d.duration = 60;
  const Outcome walk = simulate(d);
  EXPECT_TRUE(walk.boardings.empty());
  EXPECT_EQ(walk.exited, 0u);
}

// Stairs and an escalator: at 0.5 m/s the escalator (25 s of riding) is slower than the stairs, and
// everyone climbs; at 2 m/s it is quicker for the first to choose, until the queue they form makes
// the stairs as quick — some ride, the rest walk, and all leave.
TEST(TransportChoice, PeopleRideOnlyWhenThatIsQuickerCountingTheQueue) {
  const Outcome slow = simulate(splitLevel(0.5f, 20));
  EXPECT_TRUE(slow.boardings.empty());
  EXPECT_EQ(slow.exited, 20u);
  const Outcome fast = simulate(splitLevel(2.0f, 20));
  ASSERT_EQ(fast.boardings.count(0), 1u);
  EXPECT_GE(fast.boardings.at(0), 3u);
  EXPECT_LE(fast.boardings.at(0), 17u);
  EXPECT_EQ(fast.exited, 20u);
}

// An escalator and a lift side by side: people spread over both by the waits they expect (each
// escalator rider adds a headway, each full car a round trip), and everyone is out sooner than when
// the escalator is the only way; the same on one thread and on three.
TEST(TransportChoice, PeopleSpreadOverALiftAndAnEscalatorByTheWaitTheyExpect) {
  sim::ScenarioDesc only = splitLevel(0.5f, 40, false);
  const Outcome escalatorOnly = simulate(only);
  ASSERT_EQ(escalatorOnly.exited, 40u);
  sim::ScenarioDesc both = only;
  both.points.push_back(region("lift-low", sim::PointKind::Interest, 9.0f, 11.0f, 1.0f, 3.0f, 0.0f));   // 3
  both.points.push_back(region("lift-high", sim::PointKind::Interest, 21.0f, 23.0f, 1.0f, 3.0f, 4.0f));  // 4
  both.transports.push_back(transport("lift", sim::TransportKind::Elevator, 3, 4, 1.0f));
  const Outcome spread = simulate(both);
  EXPECT_EQ(spread.exited, 40u);
  ASSERT_EQ(spread.boardings.size(), 2u);
  EXPECT_GE(spread.boardings.at(3), 4u);   // the lift
  EXPECT_GE(spread.boardings.at(0), 20u);  // the escalator
  EXPECT_LT(spread.lastExit, escalatorOnly.lastExit - 5.0);
  EXPECT_EQ(simulate(both, 3).hash, spread.hash);
}

// A crowd inserted at run time with a goal of its own upstairs rides too: its goal's field is built
// when its first group weighs the way there.
TEST(TransportChoice, ACrowdInsertedAtRunTimeRidesToItsOwnGoalUpstairs) {
  const sim::ScenarioDesc d = splitLevel(0.5f, 4, false);
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  sim::World& w = *created.value();
  core::TaskSystem tasks(1);
  sim::CrowdDesc crowd;
  crowd.id = "late";
  crowd.basePoints = static_cast<std::uint32_t>(d.points.size());
  crowd.basePopulations = static_cast<std::uint32_t>(d.populations.size());
  crowd.points.push_back(region("lounge", sim::PointKind::Interest, 26.0f, 28.0f, 6.0f, 8.0f, 4.0f));  // point 3
  sim::PopulationDesc p = d.populations[0];
  p.id = "late-people";
  p.groups = 6;
  p.goals = {3};
  crowd.populations.push_back(p);
  for (int i = 0; i < 100; ++i) w.step(tasks);
  ASSERT_TRUE(w.insertCrowd(crowd).ok());
  std::map<std::uint32_t, std::uint32_t> boardings, reached;
  while (w.stats().time < 150.0) {
    w.step(tasks);
    const auto f = w.takeFrame();
    for (const sim::Event& e : f->events) {
      if (e.kind == sim::EventKind::WaypointChosen) ++boardings[e.a];
      if (e.kind == sim::EventKind::GoalReached) ++reached[e.a];
    }
  }
  EXPECT_EQ(boardings[0], 4u + 6u);  // the scenario's four (their events wait for the first frame taken) and the crowd's six
  EXPECT_EQ(reached[3], 6u);
}

// A door closes at the stair's foot (an exit point cut into the floor there, nobody's goal) at 20 s,
// after six people have climbed the stair (the escalator, 25 s of riding, is slower) and before
// twelve more set off at 25 s: the walking distances, measured when the first six chose, are
// measured anew on the mesh with the door closed, so the twelve ride. Red when the fields are not
// rebuilt on a door change (TransportRoutes::meshChanged): the twelve then head for the closed
// stair, and nobody rides.
TEST(TransportChoice, ADoorClosedOnTheStairsSendsLaterPeopleToTheEscalator) {
  sim::ScenarioDesc d = splitLevel(0.5f, 6);
  d.duration = 200;
  d.points.push_back(region("gate", sim::PointKind::Exit, 11.0f, 12.0f, 0.0f, 3.5f, 0.0f));
  sim::PopulationDesc late = d.populations[0];
  late.id = "late";
  late.groups = 12;
  late.start = 25.0f;
  d.populations.push_back(late);
  d.timeline = {test::doorAt(20.0f, sim::TimelineAction::CloseExit, 3)};
  const Outcome closed = simulate(d);
  ASSERT_EQ(closed.boardings.count(0), 1u) << "nobody rode";
  EXPECT_EQ(closed.boardings.at(0), 12u) << "the twelve who set off after the door closed";
  EXPECT_EQ(closed.exited, 18u);
  d.timeline.clear();  // the gate open: everyone climbs, as in PeopleRideOnlyWhenThatIsQuickerCountingTheQueue
  const Outcome open = simulate(d);
  EXPECT_TRUE(open.boardings.empty());
  EXPECT_EQ(open.exited, 18u);
}

// Most people ride an escalator even when the stairs beside it are quicker (Zacharias & Ling 2014:
// 20.3 % of shoppers climbed): with the defaults, of 60 groups going up with a 0.5 m/s escalator
// (25 s of riding, slower than the stairs) a fifth climb and the rest ride, each group drawing for
// itself, the same on one thread and on three. All climb when the share going up is 1 (the time
// choice of PeopleRideOnlyWhenThatIsQuickerCountingTheQueue) and all ride when it is 0, whatever
// the share going down.
TEST(TransportChoice, MostPeopleRideEvenWhenTheStairsBesideAreQuicker) {
  sim::ScenarioDesc d = splitLevel(0.5f, 60);
  d.populations[0].stairClimbUp = 0.203f;
  d.populations[0].stairClimbDown = 0.311f;
  d.duration = 400;
  const Outcome shares = simulate(d);
  ASSERT_EQ(shares.boardings.count(0), 1u) << "nobody rode";
  const std::uint32_t climbed = 60 - shares.boardings.at(0);
  EXPECT_GE(climbed, 4u);   // 12 expected; a binomial draw of 60 at 0.203 lies in 4–20 but for 1 in 1000
  EXPECT_LE(climbed, 20u);
  EXPECT_EQ(shares.exited, 60u);
  EXPECT_EQ(simulate(d, 3).hash, shares.hash);

  d.populations[0].stairClimbUp = 0.0f;
  d.populations[0].stairClimbDown = 1.0f;  // going down does not count here
  const Outcome ride = simulate(d);
  ASSERT_EQ(ride.boardings.count(0), 1u);
  EXPECT_EQ(ride.boardings.at(0), 60u);
  EXPECT_EQ(ride.exited, 60u);

  d.populations[0].stairClimbUp = 1.0f;
  d.populations[0].stairClimbDown = 0.0f;
  const Outcome climb = simulate(d);
  EXPECT_TRUE(climb.boardings.empty());
  EXPECT_EQ(climb.exited, 60u);
}

// Someone who does not take the stairs boards on its own floor: with a down escalator beside the up
// one and a long queue at the up one, walking up the stairs to ride down (and then riding up, or
// walking on) is a way, and it was the one non-climbers took once the queue grew when every ride
// from anywhere was weighed (in the department store a third of the walkers up the stairs had not
// chosen to climb). Red without the floor check in TransportRoutes::boardingFor.
TEST(TransportChoice, PeopleWhoDoNotClimbBoardOnTheirOwnFloor) {
  sim::ScenarioDesc d = splitLevel(0.5f, 60, true, 0.0f);
  d.duration = 400;
  d.points.push_back(region("down-head", sim::PointKind::Interest, 21.0f, 23.0f, 1.0f, 3.0f, 4.0f));  // 3
  d.points.push_back(region("down-foot", sim::PointKind::Interest, 9.0f, 11.0f, 1.0f, 3.0f, 0.0f));   // 4
  d.transports.push_back(transport("escalator-down", sim::TransportKind::Escalator, 3, 4, 0.5f));
  const Outcome o = simulate(d);
  EXPECT_EQ(o.boardings.count(3), 0u) << "boarded the down escalator upstairs";
  ASSERT_EQ(o.boardings.count(0), 1u);
  EXPECT_EQ(o.boardings.at(0), 60u);
  EXPECT_EQ(o.exited, 60u);
}

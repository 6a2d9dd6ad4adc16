// Tests for exit choice (libs/sim/src/exit_choice.cpp; docs/crowd-model.md "Tactical level: exit
// choice"): the RiMEA 11 room — two 1 m doors in the east wall, a crowd in its southern half —
// with each rule: "nearest" sends each person to the door nearest by walking distance, "quickest"
// spreads the crowd over both doors by their queues and empties the room sooner, "allocation"
// splits by shares and never re-evaluates; a high hysteresis keeps every first choice; a closed
// exit is left for the other (and nobody leaves by it after it closed); a closed door lets nobody
// through: with every exit closed, or a fixed goal at a closed exit, people wait at the door until
// it opens; World::setExitOpen closes and opens a door on an event the caller sees; trajectories are
// the same for 1 and 4 threads.
#include <gtest/gtest.h>

#include <map>

#include "sim_test_util.hpp"
#include "timeline.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

/// ExitChosen's b for a first choice (no exit before).
constexpr std::uint32_t kFirstChoice = 0xffffffffu;

core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

sim::PointDesc exitPoint(std::string id, float y) {
  sim::PointDesc p;
  p.id = std::move(id);
  p.kind = sim::PointKind::Exit;
  p.polygon = rect(20.6f, y - 0.5f, 21.6f, y + 0.5f);
  p.position = {21.1f, y};
  return p;
}

/// A 20 x 10 m room, doors centred at y 2 ("south", point 0) and 8 ("north", point 1) into a 2 m
/// hall; `agents` start in x 5..19.7, y 0.3..4.5: the south door is the nearer one for all.
sim::ScenarioDesc room(std::uint32_t agents, sim::ExitChoiceDesc choice) {
  sim::ScenarioDesc d;
  d.seed = 5;
  d.duration = 400.0f;
  d.walkable = {rect(0, 0, 20, 10), rect(20.2f, 0, 22.2f, 10), rect(20, 1.5f, 20.2f, 2.5f), rect(20, 7.5f, 20.2f, 8.5f)};
  d.points = {exitPoint("south", 2.0f), exitPoint("north", 8.0f)};
  sim::PopulationDesc p;
  p.id = "crowd";
  p.groups = agents;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = rect(5, 0.3f, 19.7f, 4.5f);
  p.speedMean = 1.34f;
  p.speedSd = 0.26f;
  p.exits = {0, 1};
  p.exitChoice = std::move(choice);
  d.populations = {p};
  return d;
}

struct Outcome {
  std::map<std::uint32_t, int> exitsBy;  // exit point → agents who left by it
  int firstChoices = 0, changes = 0;
  std::map<std::uint32_t, int> firstBy;  // exit point → groups that chose it first
  double lastExit = 0.0;
  std::vector<sim::Event> events;
};

Outcome run(const sim::ScenarioDesc& d, int threads = 1, double seconds = 400.0) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  Outcome o;
  if (!created.ok()) return o;
  o.events = sim::test::runEvents(*created.value(), seconds, threads);
  for (const sim::Event& e : o.events) {
    if (e.kind == sim::EventKind::Exit) ++o.exitsBy[e.a], o.lastExit = static_cast<double>(e.tick) * d.dt;
    if (e.kind == sim::EventKind::ExitChosen && e.b == kFirstChoice) ++o.firstChoices, ++o.firstBy[e.a];
    if (e.kind == sim::EventKind::ExitChosen && e.b != kFirstChoice) ++o.changes;
  }
  return o;
}

TEST(ExitChoice, NearestSendsEachPersonToTheDoorNearestByWalking) {
  sim::ExitChoiceDesc c;
  c.rule = sim::ExitRule::Nearest;
  Outcome o = run(room(200, c));
  EXPECT_EQ(o.firstChoices, 200);
  EXPECT_EQ(o.firstBy[0], 200);
  // Those the queue at the south door pushes north of y 5 find the north door nearer and change.
  EXPECT_GT(o.exitsBy[0], 90);
  EXPECT_EQ(o.exitsBy[0] + o.exitsBy[1], 200);
}

TEST(ExitChoice, QuickestSpreadsTheCrowdAndEmptiesTheRoomSooner) {
  sim::ExitChoiceDesc quick, near;
  near.rule = sim::ExitRule::Nearest;
  Outcome q = run(room(300, quick));
  Outcome n = run(room(300, near));
  ASSERT_EQ(q.exitsBy[0] + q.exitsBy[1], 300);
  ASSERT_EQ(n.exitsBy[0] + n.exitsBy[1], 300);
  // Both doors carry a good share.
  EXPECT_GT(q.exitsBy[0], 100);
  EXPECT_GT(q.exitsBy[1], 100);
  EXPECT_GT(q.changes, 10);  // the queue at the south door made people change their minds
  EXPECT_LT(q.lastExit, n.lastExit - 3.0) << "quickest " << q.lastExit << " s (" << q.exitsBy[0] << "/" << q.exitsBy[1]
                                          << "), nearest " << n.lastExit << " s (" << n.exitsBy[0] << "/" << n.exitsBy[1] << ")";
}

TEST(ExitChoice, FamiliarityDrawsPeopleToTheExitTheyKnow) {
  // Everybody starts nearer the south door; knowing only the north one, most walk there, and more
  // the dearer an unknown exit looks.
  sim::ExitChoiceDesc plain, mild, strong;
  plain.rule = mild.rule = strong.rule = sim::ExitRule::Nearest;
  mild.familiar = strong.familiar = {1};
  mild.familiarity = 1.2f;
  strong.familiarity = 3.0f;
  Outcome p = run(room(200, plain)), m = run(room(200, mild)), s = run(room(200, strong));
  ASSERT_EQ(s.exitsBy[0] + s.exitsBy[1], 200);
  EXPECT_EQ(p.firstBy[1], 0);        // without familiarity nobody first picks the north door
  EXPECT_GT(m.firstBy[1], 10);       // at 1.2 those in the north of the spawn area do
  EXPECT_LT(m.firstBy[1], 150);
  EXPECT_GE(s.firstBy[1], 180);      // at 3 nearly everybody does
  // Familiarity is no blindness: walking past the south door, some still take it (measured: 143 of
  // 200 out by the north door at 3, 99 without familiarity, the queue sending the rest north).
  EXPECT_GT(s.exitsBy[1], p.exitsBy[1] + 25);
  // Knowing only the south door, the nearer, changes nothing for the first choices.
  sim::ExitChoiceDesc south = plain;
  south.familiar = {0};
  EXPECT_EQ(run(room(200, south)).firstBy[0], 200);
}

TEST(ExitChoice, HerdingFollowsWhereThePeopleAroundAreGoing) {
  // 40 choosers nearer the south door among 20 who all walk to the north one (few enough that
  // walking, not the queues, decides): with herding the choosers go where those around them go;
  // the "leaders" population has no choice (goals only).
  auto scenario = [](float herding, std::uint64_t seed) {
    sim::ExitChoiceDesc c;
    c.herding = herding;
    sim::ScenarioDesc d = room(40, c);
    d.seed = seed;
    sim::PopulationDesc leaders = d.populations[0];
    leaders.id = "leaders";
    leaders.groups = 20;
    leaders.exits.clear();
    leaders.exitChoice = {};
    leaders.goals = {1};
    d.populations.push_back(leaders);
    return d;
  };
  auto choosersNorth = [](const Outcome& o) {
    int north = 0;
    for (const sim::Event& e : o.events) north += e.kind == sim::EventKind::Exit && e.a == 1 && e.agent < 40 ? 1 : 0;
    return north;
  };
  // Over three seeds (one alone is noisy: 40 choosers): measured 48 with herding against 28 without.
  int withHerding = 0, without = 0;
  for (const std::uint64_t seed : {5u, 6u, 7u}) {
    Outcome none = run(scenario(0.0f, seed)), some = run(scenario(0.8f, seed));
    EXPECT_EQ(none.exitsBy[0] + none.exitsBy[1], 60);
    EXPECT_EQ(some.exitsBy[0] + some.exitsBy[1], 60);
    withHerding += choosersNorth(some);
    without += choosersNorth(none);
  }
  EXPECT_GT(withHerding, without + 15) << withHerding << " vs " << without;
}

TEST(ExitChoice, AllocationSplitsBySharesAndNeverReconsiders) {
  sim::ExitChoiceDesc c;
  c.rule = sim::ExitRule::Allocation;
  c.shares = {3.0f, 1.0f};
  Outcome o = run(room(400, c));
  EXPECT_EQ(o.firstChoices, 400);
  EXPECT_NEAR(o.firstBy[0] / 400.0, 0.75, 0.07);
  EXPECT_EQ(o.changes, 0);
  EXPECT_EQ(o.exitsBy[0], o.firstBy[0]);
}

TEST(ExitChoice, FullHysteresisKeepsEveryFirstChoice) {
  sim::ExitChoiceDesc c;
  c.hysteresis = 1.0f;
  Outcome o = run(room(300, c));
  EXPECT_EQ(o.changes, 0);
  EXPECT_EQ(o.exitsBy[0], o.firstBy[0]);
}

TEST(ExitChoice, AClosedExitIsLeftForTheOther) {
  sim::ExitChoiceDesc c;
  auto d = room(200, c);
  sim::TimelineEntry close;
  close.time = 10.0f;
  close.action = sim::TimelineAction::CloseExit;
  close.point = 1;  // north
  d.timeline = {close};
  Outcome o = run(d);
  EXPECT_EQ(o.exitsBy[0] + o.exitsBy[1], 200);
  int northAfter = 0;
  for (const sim::Event& e : o.events) {
    if (e.kind == sim::EventKind::Exit && e.a == 1 && static_cast<double>(e.tick) * d.dt > 10.5) ++northAfter;
  }
  EXPECT_EQ(northAfter, 0) << "people left by the north exit after it closed";
  EXPECT_GT(o.exitsBy[0], 170);
}

/// Exit events between `from` and `to` [s].
int exitsBetween(const Outcome& o, const sim::ScenarioDesc& d, double from, double to) {
  int n = 0;
  for (const sim::Event& e : o.events) {
    const double t = static_cast<double>(e.tick) * d.dt;
    if (e.kind == sim::EventKind::Exit && t >= from && t < to) ++n;
  }
  return n;
}

TEST(ExitChoice, NobodyLeavesThroughAClosedDoorEvenWithNoOtherOpen) {
  // Both doors close at 5 s and open again at 40 s: those at a door wait there, nobody leaves in
  // between (before, a group with no open exit kept going and left through the closed one).
  sim::ExitChoiceDesc c;
  c.rule = sim::ExitRule::Nearest;
  auto d = room(100, c);
  d.timeline = {test::doorAt(5, sim::TimelineAction::CloseExit, 0), test::doorAt(5, sim::TimelineAction::CloseExit, 1),
                test::doorAt(40, sim::TimelineAction::OpenExit, 0), test::doorAt(40, sim::TimelineAction::OpenExit, 1)};
  const Outcome o = run(d, 1, 200.0);
  EXPECT_EQ(exitsBetween(o, d, 5.0, 40.0), 0) << "people left through a closed door";
  EXPECT_EQ(o.exitsBy.at(0) + (o.exitsBy.count(1) != 0 ? o.exitsBy.at(1) : 0), 100);
  EXPECT_GT(exitsBetween(o, d, 40.0, 200.0), 50) << "the crowd waiting at the doors left once they opened";
}

TEST(ExitChoice, AFixedGoalAtAClosedExitWaitsForItToOpen) {
  // No exit choice: the population's goals end at the south door, which is closed from 0 to 30 s.
  auto d = room(60, {});
  d.populations[0].exits.clear();
  d.populations[0].goals = {0};
  d.timeline = {test::doorAt(0, sim::TimelineAction::CloseExit, 0), test::doorAt(30, sim::TimelineAction::OpenExit, 0)};
  const Outcome o = run(d, 1, 150.0);
  EXPECT_EQ(exitsBetween(o, d, 0.0, 30.0), 0);
  EXPECT_EQ(o.exitsBy.at(0), 60);
}

TEST(ExitChoice, ADoorClosedOnAnEventSendsTheCrowdToTheOther) {
  // The caller closes the south door once 20 people have left by it (an event it sees), through
  // World::setExitOpen: from the next tick nobody leaves by it and everybody else takes the north.
  sim::ExitChoiceDesc c;
  c.rule = sim::ExitRule::Nearest;
  const auto d = room(100, c);
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok());
  sim::World& w = *created.value();
  EXPECT_FALSE(w.setExitOpen("nowhere", false));
  core::TaskSystem tasks(1);
  int south = 0, north = 0, southAfterClosing = 0;
  bool closed = false;
  while (w.stats().time < 300.0 && !w.finished()) {
    w.step(tasks);
    const auto frame = w.takeFrame();  // held: the range below must not outlive it
    for (const sim::Event& e : frame->events) {
      if (e.kind != sim::EventKind::Exit) continue;
      (e.a == 0 ? south : north) += 1;
      if (e.a == 0 && closed) ++southAfterClosing;
    }
    if (!closed && south >= 20) closed = w.setExitOpen("south", false);
  }
  EXPECT_TRUE(closed);
  EXPECT_EQ(southAfterClosing, 0);
  EXPECT_EQ(south + north, 100);
  EXPECT_GT(north, 50);
}

TEST(ExitChoice, SetExitOpenRefusesAPointThatIsNotAnExit) {
  auto d = room(10, {});
  sim::PointDesc hall;
  hall.id = "hall";
  hall.kind = sim::PointKind::Interest;
  hall.position = {10, 5};
  d.points.push_back(hall);
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok());
  EXPECT_FALSE(created.value()->setExitOpen("hall", false));
  EXPECT_FALSE(created.value()->setExitOpen("", true));
  EXPECT_TRUE(created.value()->setExitOpen("north", true));
}

TEST(ExitChoice, SameTrajectoriesFor1And4Threads) {
  // 1200 agents: several chunks of the parallel phases.
  sim::ExitChoiceDesc c;
  auto d = room(1200, c);
  d.walkable[0] = rect(0, 0, 20, 40);
  d.walkable[1] = rect(20.2f, 0, 22.2f, 40);
  d.populations[0].spawn.polygon = rect(1, 0.3f, 19.7f, 39.7f);
  auto a = sim::World::create(d), b = sim::World::create(d);
  ASSERT_TRUE(a.ok() && b.ok());
  core::TaskSystem one(1), four(4);
  for (int t = 0; t < 400; ++t) {
    a.value()->step(one);
    b.value()->step(four);
    const auto fa = a.value()->takeFrame(), fb = b.value()->takeFrame();
    ASSERT_EQ(fa->size(), fb->size());
    for (std::size_t i = 0; i < fa->size(); ++i) {
      ASSERT_EQ(fa->posX[i], fb->posX[i]) << "tick " << t;
      ASSERT_EQ(fa->posY[i], fb->posY[i]) << "tick " << t;
    }
  }
}

}  // namespace

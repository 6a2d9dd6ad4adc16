// Tests for closed doors (libs/sim/src/insert.cpp World::Impl::closeDoorFloor, nav::NavMesh::setClosed;
// docs/crowd-model.md "Closed exits"): a closed exit is a wall. Two rooms joined by two doors,
// each an exit point in the wall's opening (a door in the middle of the world, nobody's goal): with
// the south door closed everyone walks through the north one and nobody's centre is ever in the
// closed door; those already on their way re-plan; once it opens it is used again. An exit on the
// boundary that is a population's goal keeps its people waiting in front of it, outside its area.
// Someone standing in a doorway when it closes steps out. (Path searches under way when a door
// closes give the same results on any thread count: PathQueue.DoorsClosingUnderWay*.)
// Exit choice measures round closed doors (ExitChoice::refresh): with the inner door between a
// crowd and the exit nearest it closed, that exit is the long way round (or out of reach) and the
// groups take the other; when the door opens they come back.
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "sim_test_util.hpp"
#include "timeline.hpp"
#include "throng/sim/world.hpp"

using namespace throng;

namespace {

core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

sim::PointDesc exitRect(std::string id, core::Polygon polygon) {
  sim::PointDesc p;
  p.id = std::move(id);
  p.kind = sim::PointKind::Exit;
  p.position = core::centroid(polygon);
  p.polygon = std::move(polygon);
  return p;
}

// The doors' areas: the 1.2 m openings in the 0.2 m wall at x 10..10.2, 0.4 m deep into each room.
const core::Polygon kSouthDoor = rect(9.6f, 1.9f, 10.6f, 3.1f);
const core::Polygon kNorthDoor = rect(9.6f, 6.9f, 10.6f, 8.1f);

/// Two 10 x 10 m rooms; points: 0 the south door (y 1.9..3.1), 1 the north door (6.9..8.1), 2 the
/// way out along the east room's east wall (wall to wall). `agents` start in the west room's south (x 1..8,
/// y 0.5..4): the south door is the nearer for all of them.
sim::ScenarioDesc twoRooms(std::uint32_t agents) {
  sim::ScenarioDesc d;
  d.seed = 3;
  d.duration = 300.0f;
  d.walkable = {rect(0, 0, 10, 10), rect(10.2f, 0, 20, 10), rect(10, 1.9f, 10.2f, 3.1f), rect(10, 6.9f, 10.2f, 8.1f)};
  d.points = {exitRect("south", kSouthDoor), exitRect("north", kNorthDoor), exitRect("out", rect(19, 0, 20, 10))};
  sim::PopulationDesc p;
  p.id = "crowd";
  p.groups = agents;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = rect(1, 0.5f, 8, 4);
  p.goals = {2};
  d.populations = {p};
  return d;
}

bool inside(const core::Polygon& poly, float x, float y) { return core::pointInPolygon(poly, {x, y}); }

struct Crossings {
  int south = 0, north = 0;          ///< agents whose centre went from the west room into the east one
  int insideWhileClosed = 0;         ///< agent-ticks with a centre in the watched area while it was closed
  int left = 0;                      ///< Exit events
  int mostInFront = 0;               ///< most agents at one tick in the metre in front of the south door, 2 s after it closed
  float longestStep = 0.0f;          ///< the longest move of an agent between two frames [m]
};

/// Steps until `seconds`; the area `watched` (the south door unless said) is closed over
/// [closedFrom, closedUntil) [s].
Crossings walk(sim::World& w, double seconds, double closedFrom, double closedUntil,
               const core::Polygon& watched = kSouthDoor, int threads = 1) {
  core::TaskSystem tasks(threads);
  Crossings c;
  std::vector<float> lastX, lastY;  // by stable id
  std::vector<std::uint8_t> over;  // by stable id: crossed already (each agent counts once)
  while (w.stats().time < seconds && !w.finished()) {
    w.step(tasks);
    const auto f = w.takeFrame();
    const double t = w.stats().time;
    for (const sim::Event& e : f->events) c.left += e.kind == sim::EventKind::Exit ? 1 : 0;
    int inFront = 0;
    for (std::size_t i = 0; i < f->size(); ++i) {
      const std::uint32_t id = f->ids[i];
      if (lastX.size() <= id) {
        lastX.resize(id + 1, -1.0f);
        lastY.resize(id + 1, -1.0f);
        over.resize(id + 1, 0);
      }
      const float x = f->posX[i], y = f->posY[i];
      if (lastX[id] >= 0.0f) c.longestStep = std::max(c.longestStep, std::hypot(x - lastX[id], y - lastY[id]));
      if (lastX[id] >= 0.0f && lastX[id] < 10.1f && x >= 10.1f && over[id] == 0) {
        (y < 5.0f ? c.south : c.north) += 1;
        over[id] = 1;
      }
      lastX[id] = x;
      lastY[id] = y;
      // A tick's frame shows the tick's end; a door closed at `closedFrom` is closed from the
      // tick that ends after it.
      if (t > closedFrom + 0.01 && t < closedUntil && inside(watched, x, y)) ++c.insideWhileClosed;
      inFront += x > 8.6f && x < 9.6f && y > 1.6f && y < 3.4f ? 1 : 0;
    }
    if (t > closedFrom + 2.0 && t < closedUntil) c.mostInFront = std::max(c.mostInFront, inFront);
  }
  return c;
}

TEST(ClosedDoor, EveryoneWalksThroughTheOtherDoorAndNobodyStandsInTheClosedOne) {
  // Both doors open, the south one is the way of most (24-29 of 40 as the model changed; the
  // exit's targets span the east wall, so those drawn in its north part go by the north door);
  // closed from the start, of none.
  auto open = sim::World::create(twoRooms(40));
  ASSERT_TRUE(open.ok()) << core::formatAll(open.errors());
  const Crossings o = walk(*open.value(), 200.0, 0.0, 0.0);
  EXPECT_GT(o.south, 20) << "most of the 40 take the nearer door";
  EXPECT_EQ(o.left, 40);
  auto d = twoRooms(40);
  d.timeline = {test::doorAt(0, sim::TimelineAction::CloseExit, 0)};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok());
  const Crossings c = walk(*created.value(), 200.0, 0.0, 1e9);
  EXPECT_EQ(c.insideWhileClosed, 0) << "agent centres inside the closed door";
  EXPECT_EQ(c.south, 0) << "people walked through the closed door";
  EXPECT_EQ(c.north, 40);
  EXPECT_EQ(c.left, 40);
}

TEST(ClosedDoor, ThoseOnTheirWayReplanAndTheReopenedDoorIsUsedAgain) {
  // The south door closes at 3 s, when the crowd is on its way to it, and opens at 40 s; a second
  // crowd starts from the same place at 45 s. Re-planning at once, few walk on to the closed door
  // (3 at most in the metre in front of it; 12 when they re-plan only after their progress check).
  auto d = twoRooms(40);
  sim::PopulationDesc later = d.populations[0];
  later.id = "later";
  later.start = 45.0f;
  d.populations.push_back(later);
  d.timeline = {test::doorAt(3, sim::TimelineAction::CloseExit, 0), test::doorAt(40, sim::TimelineAction::OpenExit, 0)};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok());
  sim::World& w = *created.value();
  // Until the door opens: those who had not passed it go north; nobody is inside it.
  const Crossings before = walk(w, 40.0, 3.0, 40.0);
  EXPECT_EQ(before.insideWhileClosed, 0);
  EXPECT_GT(before.north, 20) << "the crowd kept to its old way";
  EXPECT_LE(before.mostInFront, 5) << "people walked on to the closed door instead of re-planning at once";
  EXPECT_EQ(before.south + before.north, 40);
  // After: the second crowd takes the south door again (22 of 40 did, as with the door never closed).
  const Crossings after = walk(w, 200.0, 0.0, 0.0);
  EXPECT_GT(after.south, 15) << "the reopened door was not used";
  EXPECT_EQ(before.left + after.left, 80);
}

TEST(ClosedDoor, PeopleWhoseGoalIsAClosedExitWaitInFrontOfIt) {
  // The way out along the east wall is closed from 0 to 30 s: its people wait in front of it,
  // outside its area, and leave by it once it opens.
  auto d = twoRooms(8);
  d.timeline = {test::doorAt(0, sim::TimelineAction::CloseExit, 2), test::doorAt(30, sim::TimelineAction::OpenExit, 2)};
  const core::Polygon out = d.points[2].polygon;
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok());
  sim::World& w = *created.value();
  const Crossings before = walk(w, 29.0, 0.0, 30.0, out);
  EXPECT_EQ(before.left, 0);
  EXPECT_EQ(before.insideWhileClosed, 0);
  const auto f = w.takeFrame();
  int near = 0;
  for (std::size_t i = 0; i < f->size(); ++i) near += f->posX[i] > 16.0f && f->posX[i] < 19.0f ? 1 : 0;
  EXPECT_EQ(near, 8) << "the crowd does not wait in front of the way out";
  const Crossings after = walk(w, 40.0, 0.0, 0.0);
  printf("left by 40: %d\n", after.left);
  EXPECT_EQ(after.left, 8);
}

TEST(ClosedDoor, SomeoneStandingInTheDoorwayStepsOutWhenItCloses) {
  // Three people stop in and around the south doorway for 60 s (an action point there); the door
  // closes at 2 s: those in it step out to the nearest open floor at once, though not walking.
  auto d = twoRooms(3);
  sim::PointDesc stand;
  stand.id = "stand";
  stand.kind = sim::PointKind::Action;
  stand.position = {10.1f, 2.5f};
  stand.radius = 0.3f;
  stand.stop = true;
  stand.actionDuration = 60.0f;
  d.points.push_back(stand);
  d.populations[0].spawn.polygon = rect(8.5f, 2.0f, 9.5f, 3.0f);
  d.populations[0].goals = {3};
  d.timeline = {test::doorAt(2, sim::TimelineAction::CloseExit, 0)};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  sim::World& w = *created.value();
  walk(w, 1.9, 0.0, 0.0);
  const auto f = w.takeFrame();
  int inDoor = 0;
  for (std::size_t i = 0; i < f->size(); ++i) inDoor += inside(kSouthDoor, f->posX[i], f->posY[i]) ? 1 : 0;
  ASSERT_GE(inDoor, 1) << "nobody is standing in the doorway";
  const Crossings closed = walk(w, 20.0, 2.0, 1e9);
  EXPECT_EQ(closed.insideWhileClosed, 0) << "agent centres stayed in the closed door";
}

/// ExitChosen's b for a first choice (no exit before).
constexpr std::uint32_t kFirstChoice = 0xffffffffu;

/// A 20 x 20 m west room and a 10 x 20 m east room joined by an inner door in the south (point 0,
/// y 1.9..3.1) and, when `northDoor`, a door in the north (point 1, y 16.9..18.1; without it
/// point 1 marks the wall there). Exits: "near" (point 2) in the east room just behind the inner
/// door, "far" (point 3) on the west room's west wall. `groups` single people start in x 18..19.4,
/// y 1.5..3.5, in front of the inner door: "near" is 2-3 m away through it, about 28 m round by the
/// north door; "far" about 18 m.
sim::ScenarioDesc innerDoor(std::uint32_t groups, bool northDoor, sim::ExitChoiceDesc choice) {
  sim::ScenarioDesc d;
  d.seed = 7;
  d.duration = 300.0f;
  d.walkable = {rect(0, 0, 20, 20), rect(20.2f, 0, 30, 20), rect(20, 1.9f, 20.2f, 3.1f)};
  if (northDoor) d.walkable.push_back(rect(20, 16.9f, 20.2f, 18.1f));
  d.points = {exitRect("inner", rect(19.6f, 1.9f, 20.6f, 3.1f)), exitRect("north", rect(19.6f, 16.9f, 20.6f, 18.1f)),
              exitRect("near", rect(21, 1.5f, 22, 3.5f)), exitRect("far", rect(0, 1, 0.8f, 4))};
  sim::PopulationDesc p;
  p.id = "crowd";
  p.groups = groups;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = rect(18, 1.5f, 19.4f, 3.5f);
  p.exits = {2, 3};
  p.exitChoice = std::move(choice);
  d.populations = {p};
  return d;
}

struct Choices {
  std::map<std::uint32_t, int> firstBy, changedTo, leftBy;  // exit point → groups / agents
};

Choices choices(const sim::ScenarioDesc& d, double seconds) {
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : core::formatAll(created.errors()));
  Choices c;
  if (!created.ok()) return c;
  for (const sim::Event& e : sim::test::runEvents(*created.value(), seconds)) {
    if (e.kind == sim::EventKind::ExitChosen) ++(e.b == kFirstChoice ? c.firstBy : c.changedTo)[e.a];
    if (e.kind == sim::EventKind::Exit) ++c.leftBy[e.a];
  }
  return c;
}

TEST(ClosedDoor, ExitChoiceMeasuresRoundAClosedInnerDoorAndComesBackWhenItOpens) {
  // Both doors open: everybody takes "near", 2-3 m away through the inner door.
  sim::ExitChoiceDesc nearest;
  nearest.rule = sim::ExitRule::Nearest;
  Choices open = choices(innerDoor(12, true, nearest), 60.0);
  EXPECT_EQ(open.firstBy[2], 12);
  EXPECT_EQ(open.leftBy[2], 12);
  // The inner door closed from the start: "near" is ~28 m round by the north door, "far" ~18 m,
  // so everybody first heads west; the door opens at 2 s, a couple of metres on, and every group
  // turns back to "near" (then 4-5 m against ~16 m) and leaves by it.
  sim::ScenarioDesc d = innerDoor(12, true, nearest);
  d.timeline = {test::doorAt(0, sim::TimelineAction::CloseExit, 0), test::doorAt(2, sim::TimelineAction::OpenExit, 0)};
  Choices c = choices(d, 60.0);
  EXPECT_EQ(c.firstBy[3], 12) << "groups chose the exit behind the closed door (measured with it open)";
  EXPECT_EQ(c.firstBy[2], 0);
  EXPECT_EQ(c.changedTo[2], 12) << "groups did not come back when the door opened";
  EXPECT_EQ(c.leftBy[2], 12);
  // The fields are rebuilt one exit per task: the same events on 1 and 4 threads.
  auto one = sim::World::create(d), four = sim::World::create(d);
  ASSERT_TRUE(one.ok() && four.ok());
  const std::vector<sim::Event> e1 = sim::test::runEvents(*one.value(), 20.0, 1);
  const std::vector<sim::Event> e4 = sim::test::runEvents(*four.value(), 20.0, 4);
  ASSERT_EQ(e1.size(), e4.size());
  for (std::size_t i = 0; i < e1.size(); ++i) {
    EXPECT_TRUE(e1[i].tick == e4[i].tick && e1[i].agent == e4[i].agent && e1[i].kind == e4[i].kind && e1[i].a == e4[i].a &&
                e1[i].b == e4[i].b) << "event " << i << " differs between 1 and 4 threads";
  }
}

TEST(ClosedDoor, AnExitOutOfReachBehindClosedDoorsIsNeverChosen) {
  // Both doors between the rooms closed from the start: "near" cannot be reached at all. The
  // quickest rule and an allocation that sends everybody to "near" both take "far" instead, and
  // everybody leaves by it.
  sim::ExitChoiceDesc quickest, allocation;
  allocation.rule = sim::ExitRule::Allocation;
  allocation.shares = {1.0f, 0.0f};
  sim::ScenarioDesc d = innerDoor(8, true, quickest);
  sim::PopulationDesc allocated = d.populations[0];
  allocated.id = "allocated";
  allocated.exitChoice = allocation;
  d.populations.push_back(allocated);
  d.timeline = {test::doorAt(0, sim::TimelineAction::CloseExit, 0), test::doorAt(0, sim::TimelineAction::CloseExit, 1)};
  Choices c = choices(d, 90.0);
  EXPECT_EQ(c.firstBy[3], 8) << "the quickest groups chose an exit they cannot reach";
  EXPECT_EQ(c.changedTo[3], 8) << "the allocated groups kept an exit they cannot reach";
  EXPECT_EQ(c.leftBy[3], 16);
  EXPECT_EQ(c.leftBy[2], 0);
}

TEST(ClosedDoor, TheExitOfACrowdTheTimelineInsertsIsCutAndClosesAsAWall) {
  // The south door is no point of the scenario: a crowd the timeline inserts at 0 s brings it as
  // an exit, closed at once. Known when the mesh is built, it is cut: nobody walks through it. The
  // same exit brought by World::insertCrowd is not cut (exitIsWall says so; before plain floor lost
  // its kCutFlag, any polygon near the region counted as cut).
  sim::ScenarioDesc d = twoRooms(40);
  d.points.erase(d.points.begin(), d.points.begin() + 2);  // "out" is point 0 now
  d.populations[0].goals = {0};
  sim::TimelineEntry insert;
  insert.action = sim::TimelineAction::Insert;
  insert.crowd.id = "doors";
  insert.crowd.points = {exitRect("south", kSouthDoor)};
  insert.crowd.basePoints = 1;
  insert.crowd.basePopulations = 1;
  d.timeline = {insert, test::doorAt(0, sim::TimelineAction::CloseExit, 1)};
  auto created = sim::World::create(d);
  ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
  sim::World& w = *created.value();
  ASSERT_EQ(w.crowds().size(), 1u);
  EXPECT_TRUE(w.crowds()[0].applied);
  EXPECT_TRUE(w.exitIsWall("south"));
  const Crossings c = walk(w, 200.0, 0.0, 1e9);
  EXPECT_EQ(c.insideWhileClosed, 0) << "agent centres inside the closed door of the inserted crowd";
  EXPECT_EQ(c.south, 0) << "people walked through the closed door of the inserted crowd";
  EXPECT_EQ(c.left, 40);

  sim::ScenarioDesc plain = twoRooms(1);
  plain.points.erase(plain.points.begin(), plain.points.begin() + 2);
  plain.populations[0].goals = {0};
  auto api = sim::World::create(plain);
  ASSERT_TRUE(api.ok());
  sim::CrowdDesc late = insert.crowd;
  ASSERT_TRUE(api.value()->insertCrowd(late).ok());
  core::TaskSystem tasks(1);
  api.value()->step(tasks);
  EXPECT_TRUE(api.value()->exitIsWall("out"));
  EXPECT_TRUE(api.value()->exitIsWall("south")) << "an exit inserted at run time is cut when it first closes";
  EXPECT_FALSE(api.value()->exitIsWall("nothing"));
  sim::CrowdDesc nowhere;
  nowhere.id = "nowhere";
  nowhere.points = {exitRect("beyond", rect(30, 0, 31, 10))};  // no floor there: nothing to cut
  nowhere.basePoints = 2;
  nowhere.basePopulations = 1;
  ASSERT_TRUE(api.value()->insertCrowd(nowhere).ok());
  api.value()->step(tasks);
  EXPECT_FALSE(api.value()->exitIsWall("beyond"));
}

/// The two rooms without their doors' points, and a crowd that brings the south door as an exit.
struct LateDoor {
  std::unique_ptr<sim::World> world;
  Crossings before, after;  ///< before the door closed at 4 s, and from then on
  std::uint64_t hash = 0;   ///< state hash at the end
};

LateDoor closeALateDoor(int threads) {
  sim::ScenarioDesc d = twoRooms(40);
  d.points.erase(d.points.begin(), d.points.begin() + 2);  // "out" is point 0 now
  d.populations[0].goals = {0};
  auto created = sim::World::create(d);
  EXPECT_TRUE(created.ok()) << core::formatAll(created.errors());
  LateDoor r{std::move(created).value()};
  sim::World& w = *r.world;
  sim::CrowdDesc crowd;
  crowd.id = "doors";
  crowd.points = {exitRect("south", kSouthDoor)};
  crowd.basePoints = 1;
  crowd.basePopulations = 1;
  EXPECT_TRUE(w.insertCrowd(crowd).ok());
  const nav::NavMesh& first = w.navMesh();
  r.before = walk(w, 4.0, 1e9, 1e9, kSouthDoor, threads);
  EXPECT_TRUE(w.setExitOpen("south", false));
  r.after = walk(w, 200.0, 4.0, 1e9, kSouthDoor, threads);
  EXPECT_NE(&first, &w.navMesh()) << "the mesh was not rebuilt with the door cut";
  EXPECT_GT(first.polygonCount(), 0u) << "the first mesh is kept for those who hold it";
  r.hash = w.stateHash();
  return r;
}

TEST(ClosedDoor, TheExitOfACrowdInsertedAtRunTimeIsCutWhenItFirstClosesAndNobodyWalksThroughIt) {
  // World::insertCrowd brings the south door as an exit; the crowd is on its way through it when,
  // at 4 s, the door closes: the mesh is built again with the door cut, everyone turns to the
  // north door, nobody's centre enters the closed door, and all 40 leave.
  LateDoor r = closeALateDoor(1);
  EXPECT_GT(r.before.south + r.after.mostInFront, 0) << "nobody was heading for the south door: the test shows nothing";
  EXPECT_EQ(r.after.insideWhileClosed, 0) << "agent centres inside the closed door of the inserted crowd";
  EXPECT_EQ(r.after.south, 0) << "people walked through the closed door of the inserted crowd";
  EXPECT_EQ(r.before.left + r.after.left, 40);
  // Everyone finds their polygon on the new mesh where they stand: nobody jumps (a step is about
  // 0.07 m; with the old references kept, 0.22 m).
  EXPECT_LT(r.after.longestStep, 0.15f) << "someone jumped when the mesh was rebuilt";
  EXPECT_TRUE(r.world->exitIsWall("south"));
  EXPECT_EQ(closeALateDoor(3).hash, r.hash) << "the rebuilt mesh gave other trajectories on three threads";
}

}  // namespace

// Tests for libs/sim/src/phases.hpp: each phase called on its own through its context, on
// hand-built columns (no World; emit on tests/sim/goal_world.hpp), as a reader of the phase's signature would expect it to behave.
#include "phases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "goal_world.hpp"
#include "spawner.hpp"
#include "throng/sim/animation.hpp"
#include "walls.hpp"

using namespace throng;
using namespace throng::sim;

namespace {

/// The rows a phase wrote for `row` in a flat neighbour buffer.
std::vector<std::uint32_t> neighboursOf(const std::vector<std::uint32_t>& all, const std::vector<std::uint16_t>& count,
                                        std::size_t row, std::size_t k) {
  return {all.begin() + static_cast<std::ptrdiff_t>(row * k),
          all.begin() + static_cast<std::ptrdiff_t>(row * k + count[row])};
}

}  // namespace

TEST(Phases, SenseFillsNeighboursNearestFirstWithTiesByRow) {
  // Six agents on a line (x = 0, 1, 2, 3, 4 and a loner at 10); chunks of one row on two threads.
  const std::vector<float> xs{0, 1, 2, 3, 4, 10}, ys(6, 5.0f);
  SteeringDesc steering;
  steering.maxNeighbours = 3;
  steering.neighbourDistance = 3.5f;
  steering.denseNeighbourDistance = 0.0f;  // one range everywhere
  SpatialGrid grid;
  grid.configure(core::Aabb{{-1, 0}, {12, 10}}, 1.0f);
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> count;
  core::TaskSystem tasks(2);
  tasks.setGrainLimit(1);
  sense(SenseInput{xs, ys, {}, steering}, SenseOutput{grid, neighbours, count}, tasks);
  ASSERT_EQ(neighbours.size(), 6u * 3u);
  ASSERT_EQ(count.size(), 6u);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, 3), (std::vector<std::uint32_t>{1, 2, 3}));
  // Rows 1 and 3 are both 1 m from row 2, rows 0 and 4 both 2 m: ties go to the lower row.
  EXPECT_EQ(neighboursOf(neighbours, count, 2, 3), (std::vector<std::uint32_t>{1, 3, 0}));
  EXPECT_EQ(neighboursOf(neighbours, count, 4, 3), (std::vector<std::uint32_t>{3, 2, 1}));
  EXPECT_EQ(count[5], 0u) << "the loner at x = 10 is beyond neighbourDistance of everyone";
}

TEST(Phases, SenseKeepsOnlyNeighboursOnTheSameFloor) {
  // Three agents above each other's footprint: rows 0 and 2 on the ground floor, row 1 on the
  // floor above (3 m up); with floor heights given, row 1 is nobody's neighbour.
  const std::vector<float> xs{0, 0.5f, 1}, ys{0, 0, 0}, zs{0, 3, 0.2f};
  SteeringDesc steering;
  steering.denseNeighbourDistance = 0.0f;
  SpatialGrid grid;
  grid.configure(core::Aabb{{-2, -2}, {3, 2}}, 1.0f);
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> count;
  core::TaskSystem tasks(1);
  const std::size_t k = steering.maxNeighbours;
  sense(SenseInput{xs, ys, zs, steering}, SenseOutput{grid, neighbours, count}, tasks);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, k), (std::vector<std::uint32_t>{2}));
  EXPECT_EQ(count[1], 0u);
  EXPECT_EQ(neighboursOf(neighbours, count, 2, k), (std::vector<std::uint32_t>{0}));
  // Without floor heights (a flat world) all three see each other.
  sense(SenseInput{xs, ys, {}, steering}, SenseOutput{grid, neighbours, count}, tasks);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, k), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(neighboursOf(neighbours, count, 1, k), (std::vector<std::uint32_t>{0, 2}));
}

namespace {

core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

/// One group (goal list 0, empty) holding every row: enough for a GoalView.
struct OneGroup {
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> goalLists{{}};
  std::vector<std::uint32_t> group, goalCursor;
  explicit OneGroup(std::size_t rows) : group(rows, 0), goalCursor(rows, 0) { groups.add(GroupState{}); }
  [[nodiscard]] GoalView view() const { return {groups, goalLists, group, goalCursor}; }
};

}  // namespace

TEST(Phases, PlanGivesAPathOnlyToRowsThatAskedForOne) {
  // A 20 × 10 m room with a block in the middle of its lower half: row 0 asks for a path from one
  // side of the block to the other, row 1 (same places) does not.
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)},
                                  std::vector<core::Polygon>{rect(8, 0, 12, 7)}, nav::NavMeshConfig{});
  ASSERT_TRUE(mesh.ok());
  nav::PathQueue queue(mesh.value());
  const std::vector<std::uint32_t> ids{0, 1};
  const std::vector<float> xs{2, 2}, ys{2, 2}, tx{18, 18}, ty{2, 2};
  std::vector<std::uint8_t> needPath{1, 0};
  std::vector<nav::PathTicket> tickets(2, 0);
  std::vector<CornerPath> corners(2);
  std::vector<Event> events;
  const OneGroup goals(2);
  plan(PlanInput{7, ids, {}, xs, ys, tx, ty, {}, {}, goals.view()},
       PlanOutput{needPath, tickets, corners, queue, events});
  EXPECT_EQ(needPath[0], 0u) << "the request is queued";
  EXPECT_EQ(tickets[0], 0u) << "a short path completes within one tick's budget";
  ASSERT_GE(corners[0].size(), 2u) << "the path rounds the block";
  const core::Vec2 last = corners[0].data()[corners[0].size() - 1];
  EXPECT_NEAR(last.x, 18.0f, 0.05f);
  EXPECT_NEAR(last.y, 2.0f, 0.05f);
  for (std::uint32_t i = 0; i + 1 < corners[0].size(); ++i) EXPECT_GE(corners[0].data()[i].y, 7.0f) << "corner " << i;
  EXPECT_TRUE(corners[1].empty());
  EXPECT_EQ(tickets[1], 0u);
  EXPECT_TRUE(events.empty()) << "a complete path raises no PathPartial";
}

namespace {

/// One worker whose navmesh query covers a 20 × 10 m room (integrate's moveAlongSurface); no query
/// when the mesh could not be built.
std::vector<WorkerScratch> roomWorkers() {
  std::vector<WorkerScratch> workers(1);
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)}, {}, nav::NavMeshConfig{});
  if (mesh.ok()) workers[0].query = std::make_unique<nav::NavQuery>(mesh.value());
  return workers;
}

/// The navmesh polygon under each (px[r], py[r]).
std::vector<std::uint32_t> polysUnder(const std::vector<WorkerScratch>& workers, const std::vector<float>& px,
                                      const std::vector<float>& py) {
  std::vector<std::uint32_t> poly(px.size());
  for (std::size_t r = 0; r < px.size(); ++r) poly[r] = static_cast<std::uint32_t>(workers[0].query->nearest({px[r], py[r]})->second);
  return poly;
}

}  // namespace

TEST(Phases, IntegrateMovesEachRowByItsNewVelocityAlongTheMesh) {
  // Three walkers in a 20 × 10 m room, dt = 0.1 s: row 0 free (moves by newVel·dt), row 1 exited
  // (stays), row 2 half a metre from the east wall at 10 m/s (stops at the wall, on the mesh).
  std::vector<WorkerScratch> workers = roomWorkers();
  ASSERT_TRUE(workers[0].query);
  const float dt = 0.1f;
  std::vector<float> px{5, 8, 19.5f}, py{5, 5, 5}, vx(3, 0), vy(3, 0), stuck(3, 0), phase(3, 0), ox(3, 1), oy(3, 0);
  std::vector<std::uint32_t> poly = polysUnder(workers, px, py);
  std::vector<std::uint16_t> clip(3, kClipIdle);
  const std::vector<float> nvx{1.0f, 1.0f, 10.0f}, nvy{0.5f, 0.0f, 0.0f}, speed(3, 1.3f);
  const std::vector<GoalState> goalState{GoalState::Seeking, GoalState::Exited, GoalState::Seeking};
  const std::vector<AgentMode> mode(3, AgentMode::Walking);
  const std::vector<std::uint32_t> actionEnd(3, 0);
  std::vector<ChunkOutput> chunks(1);
  const OneGroup goals(3);
  core::TaskSystem tasks(1);
  integrate(IntegrateInput{dt, 0, nvx, nvy, {}, nvx, nvy, goalState, mode, speed, actionEnd, {}, {}, goals.view(), {}, {}, {}, workers},
            IntegrateOutput{px, py, {}, poly, vx, vy, stuck, clip, phase, ox, oy, chunks}, tasks);
  EXPECT_NEAR(px[0], 5.1f, 1e-5f);
  EXPECT_NEAR(py[0], 5.05f, 1e-5f);
  EXPECT_NEAR(vx[0], 1.0f, 1e-3f);
  EXPECT_NEAR(vy[0], 0.5f, 1e-3f);
  EXPECT_GT(oy[0], 0.0f) << "the heading turns toward the motion";
  EXPECT_LT(oy[0], 0.4473f) << "…over kTurnTime, not at once";
  EXPECT_EQ(clip[0], kClipWalk);
  EXPECT_EQ(px[1], 8.0f) << "an exited agent does not move";
  EXPECT_EQ(vx[1], 0.0f);
  EXPECT_LE(px[2], 20.0f - nav::NavMeshConfig{}.agentRadius + 1e-3f) << "nobody crosses a wall";
  EXPECT_GT(px[2], 19.5f);
  EXPECT_LT(vx[2], 10.0f) << "the velocity is the displacement actually made";
  EXPECT_EQ(stuck[0], 0.0f) << "walking freely is not being stuck";
  EXPECT_NEAR(chunks[0].walkingTime, 3.0 * dt, 1e-6) << "three agents in walking mode";
  EXPECT_NEAR(chunks[0].walkedDistance, std::hypot(0.1, 0.05) + (px[2] - 19.5), 1e-5);
}

TEST(Phases, IntegrateTurnsASlowBodyTowardWhereItWantsToGoNotWhereItIsShoved) {
  // Three agents facing 0.5 rad left of +x and wanting to go +x, all moved along +y: row 0 at
  // 0.3 m/s (shoved sideways in a queue) keeps turning toward +x; row 1 at 1.0 m/s (walking that
  // way) turns to +y; row 2, as row 0 but held by its model (holdHeading: turning would press its
  // body into a neighbour's), keeps its heading.
  std::vector<WorkerScratch> workers = roomWorkers();
  ASSERT_TRUE(workers[0].query);
  const float dt = 0.1f;
  std::vector<float> px{5, 10, 15}, py{5, 5, 5}, vx(3, 0), vy(3, 0), stuck(3, 0), phase(3, 0);
  const float c = std::cos(0.5f), s = std::sin(0.5f);
  std::vector<float> ox(3, c), oy(3, s);
  std::vector<std::uint32_t> poly = polysUnder(workers, px, py);
  std::vector<std::uint16_t> clip(3, kClipIdle);
  const std::vector<float> nvx{0.0f, 0.0f, 0.0f}, nvy{0.3f, 1.0f, 0.3f}, pvx(3, 1.3f), pvy(3, 0.0f), speed(3, 1.3f);
  const std::vector<std::uint8_t> hold{0, 0, 1};
  const std::vector<GoalState> goalState(3, GoalState::Seeking);
  const std::vector<AgentMode> mode(3, AgentMode::Walking);
  const std::vector<std::uint32_t> actionEnd(3, 0);
  std::vector<ChunkOutput> chunks(1);
  const OneGroup goals(3);
  core::TaskSystem tasks(1);
  integrate(IntegrateInput{dt, 0, nvx, nvy, hold, pvx, pvy, goalState, mode, speed, actionEnd, {}, {}, goals.view(), {}, {}, {}, workers},
            IntegrateOutput{px, py, {}, poly, vx, vy, stuck, clip, phase, ox, oy, chunks}, tasks);
  EXPECT_NEAR(py[0], 5.03f, 1e-4f) << "it is moved sideways";
  EXPECT_LT(oy[0], s) << "but its body turns toward where it wants to go (+x)";
  EXPECT_GT(oy[1], s) << "walking at 1 m/s, the body turns toward the motion (+y)";
  EXPECT_NEAR(py[2], 5.03f, 1e-4f) << "held, it still moves";
  EXPECT_EQ(oy[2], s) << "but its body does not turn";
  EXPECT_EQ(ox[2], c);
}

namespace {

/// The DecideOutput over every column decide may write.
DecideOutput decideOutput(AgentStore& a, std::span<ChunkOutput> chunks) {
  return {a.goalState, a.mode, a.targetX, a.targetY, a.targetZ, a.corners, a.needPath, a.goalPending,
          a.progressDistance, a.actionEndTick, a.oriX, a.oriY, a.sociologicalEffect, a.sociologicalOther,
          a.desirePoint, a.desireTrigger, chunks, a.dose};
}

/// A stopping action point at `position` of `radius`, 2 s long, facing +y.
PointDesc standingPoint(core::Vec2 position, float radius) {
  PointDesc stand;
  stand.kind = PointKind::Action;
  stand.position = position;
  stand.radius = radius;
  stand.stop = true;
  stand.actionDuration = 2.0f;
  stand.orientation = {0, 1};
  return stand;
}

/// Runs decide once, at `tick`, on rows of one group with `goalLists`, in a 20 × 10 m room;
/// returns its one chunk's output.
ChunkOutput decideOnce(const ScenarioDesc& desc, AgentStore& a, const std::vector<std::vector<std::uint32_t>>& goalLists,
                       std::uint64_t tick) {
  GroupTable groups;
  groups.add(GroupState{});
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)}, {}, nav::NavMeshConfig{});
  EXPECT_TRUE(mesh.ok());
  if (!mesh.ok()) return {};
  std::vector<WorkerScratch> workers(1);
  workers[0].query = std::make_unique<nav::NavQuery>(mesh.value());
  const CommonGroundState commonGround;
  std::vector<ChunkOutput> chunks(1);
  core::TaskSystem tasks(1);
  const GoalView goals{groups, goalLists, a.group, a.goalCursor};
  decide(DecideInput{a, desc, tick, groups, goals, commonGround, workers, {}}, decideOutput(a, chunks), tasks);
  return std::move(chunks[0]);
}

}  // namespace

TEST(Phases, DecideExitsActsAndChecksProgressRowByRow) {
  // One group whose goal list is [exit, action point]. Row 0 stands in the exit's disc, row 1 at the
  // action point's stop (goal cursor 1), row 2 far from the exit on a tick of its progress check.
  ScenarioDesc desc;
  desc.dt = 0.05f;
  desc.populations.emplace_back();
  PointDesc exit;
  exit.kind = PointKind::Exit;
  exit.position = {18, 5};
  exit.radius = 1.0f;
  desc.points = {exit, standingPoint({10, 8}, 0.5f)};
  const std::vector<std::vector<std::uint32_t>> goalLists{{0, 1}};
  AgentStore a;
  const float xs[] = {18.2f, 10.1f, 2.0f}, ys[] = {5.0f, 8.0f, 5.0f};
  for (std::uint32_t r = 0; r < 3; ++r) {
    a.addRow();
    a.id[r] = r;
    a.posX[r] = xs[r];
    a.posY[r] = ys[r];
    a.targetX[r] = r == 1 ? 10.0f : 18.0f;
    a.targetY[r] = r == 1 ? 8.0f : 5.0f;
    a.radius[r] = 0.25f;
    a.goalCursor[r] = r == 1 ? 1 : 0;
  }
  const std::uint64_t tick = 78;  // (tick + id 2) is a multiple of the 80-tick check period
  const ChunkOutput chunk = decideOnce(desc, a, goalLists, tick);

  EXPECT_EQ(a.goalState[0], GoalState::Exited);
  EXPECT_EQ(a.goalState[1], GoalState::Acting);
  EXPECT_EQ(a.mode[1], AgentMode::Acting);
  EXPECT_EQ(a.actionEndTick[1], tick + 40) << "2 s at 0.05 s per tick";
  EXPECT_EQ(a.oriY[1], 1.0f) << "facing the action point's orientation";
  EXPECT_EQ(a.goalState[2], GoalState::Seeking);
  EXPECT_EQ(a.needPath[2], 1u) << "no closer than at the last check: re-plan";
  EXPECT_FLOAT_EQ(a.progressDistance[2], 16.0f);
  EXPECT_EQ(a.needPath[0] + a.needPath[1], 0);
  ASSERT_EQ(chunk.events.size(), 2u);
  EXPECT_EQ(chunk.events[0].kind, EventKind::Exit);
  EXPECT_EQ(chunk.events[0].agent, 0u);
  EXPECT_EQ(chunk.events[1].kind, EventKind::ActionStart);
  EXPECT_EQ(chunk.events[1].a, 1u) << "the action point";
  EXPECT_TRUE(chunk.pendingRows.empty());
}

TEST(Phases, DecideReplansAWalkerOffTheFloorItsPathIsOn) {
  // A multi-level world's corners carry their floors' heights. Rows 0-2 walk the leg from a corner
  // at (6, 5) on the ground (z 0) to one at (12, 5) on the floor above (z 3), a ramp, standing
  // half-way (x 9): there the path is at z 1.5. Row 0 is on the ramp (z 1.5), row 1 on the ground
  // beneath it (z 0: pushed off), row 2 beneath it too but its corners came without heights. Rows 3
  // and 4 walk to their first corner, (9, 5) at z 3, from the ground: row 3 stands under it, row 4
  // is still 3 m short. Those off their path's floor re-plan: rows 1 and 3.
  ScenarioDesc desc;
  desc.dt = 0.05f;
  desc.populations.emplace_back();
  PointDesc goal;
  goal.position = {18, 5};
  goal.radius = 1.0f;
  desc.points = {goal};
  const std::vector<std::vector<std::uint32_t>> goalLists{{0}};
  AgentStore a;
  a.levels = true;
  const float xs[] = {9.0f, 9.0f, 9.0f, 9.1f, 6.0f}, zs[] = {1.5f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (std::uint32_t r = 0; r < 5; ++r) {
    a.addRow();
    a.id[r] = 5 * r;  // (tick + id) a multiple of the 5-tick sight period, of the 80-tick progress period never
    a.posX[r] = xs[r];
    a.posY[r] = 5.0f;
    a.posZ[r] = zs[r];
    a.targetX[r] = 18.0f;
    a.targetY[r] = 5.0f;
    a.targetZ[r] = 3.0f;
    a.radius[r] = 0.25f;
    a.progressDistance[r] = 1e30f;
    const bool ramp = r < 3;
    a.corners[r].assign(ramp ? std::vector<core::Vec2>{{6, 5}, {12, 5}} : std::vector<core::Vec2>{{9, 5}});
    a.corners[r].index = ramp ? 1 : 0;
    a.cornerZ[r] = ramp ? std::vector<float>{0.0f, 3.0f} : std::vector<float>{3.0f};
  }
  a.cornerZ[2].clear();
  decideOnce(desc, a, goalLists, 100);
  EXPECT_EQ(a.needPath[0], 0u) << "on the ramp, where its path is";
  EXPECT_EQ(a.needPath[1], 1u) << "1.5 m below its path: re-plans";
  EXPECT_EQ(a.needPath[2], 0u) << "corners without heights are not checked";
  EXPECT_EQ(a.needPath[3], 1u) << "at its first corner, a floor below it";
  EXPECT_EQ(a.needPath[4], 0u) << "short of its first corner: not judged yet";
}

TEST(Phases, DecideLetsAWalkerHeldUpNextToAnActionPointWatchFromThere) {
  // An action point of radius 0.5 m at (10, 8) whose spots are taken: row 0 is held up (stuck for
  // 2 s) 1.2 m from its centre, within the point's area + 1 m, and starts the action where it
  // stands; row 1 is as close but walks freely (no audience yet); row 2 is held up 2 m away, too far.
  ScenarioDesc desc;
  desc.dt = 0.05f;
  desc.populations.emplace_back();
  desc.points = {standingPoint({10, 8}, 0.5f)};
  const std::vector<std::vector<std::uint32_t>> goalLists{{0}};
  AgentStore a;
  const float xs[] = {10.0f, 11.2f, 10.0f}, ys[] = {6.8f, 8.0f, 6.0f};
  for (std::uint32_t r = 0; r < 3; ++r) {
    a.addRow();
    a.id[r] = r;
    a.posX[r] = xs[r];
    a.posY[r] = ys[r];
    a.targetX[r] = 10.2f;  // a spot on the far side, taken by people standing there
    a.targetY[r] = 8.2f;
    a.radius[r] = 0.2f;
    a.speed[r] = 1.2f;
    a.velY[r] = r == 1 ? 1.2f : 0.0f;
    a.stuckTime[r] = r == 1 ? 0.0f : 2.0f;
  }
  const ChunkOutput chunk = decideOnce(desc, a, goalLists, 1);
  EXPECT_EQ(a.goalState[0], GoalState::Acting) << "held up next to the area: watches from there";
  EXPECT_EQ(a.mode[0], AgentMode::Acting);
  EXPECT_EQ(a.goalState[1], GoalState::Seeking) << "walking freely: goes on to its spot";
  EXPECT_EQ(a.goalState[2], GoalState::Seeking) << "held up 2 m away: too far to watch";
  ASSERT_EQ(chunk.events.size(), 1u);
  EXPECT_EQ(chunk.events[0].kind, EventKind::ActionStart);
  EXPECT_EQ(chunk.events[0].agent, 0u);
}

TEST(Phases, FormationPullsTwoWalkersOfAFlockingGroupAbreast) {
  // A flocking pair walking east one behind the other (0.1 m apart): the group's heading is east,
  // its centroid between them, and each gets a correction toward its own side (spacing 0.75 m).
  std::vector<PopulationDesc> populations(1);
  GroupTable groups;
  GroupState pair;
  pair.expected = 2;
  pair.members.push_back(0);
  pair.members.push_back(1);
  const std::uint32_t gid = groups.add(pair);
  groups.markBusy(gid);
  groups.refreshBusy();
  const std::vector<std::uint32_t> rowOfId{0, 1}, cursor(2, 0);
  const std::vector<float> xs{5.0f, 5.1f}, ys{5.0f, 5.0f}, vx{1.0f, 1.0f}, vy{0.0f, 0.0f};
  const std::vector<GoalState> goalState(2, GoalState::Seeking);
  std::vector<float> fx(2, 9.0f), fy(2, 9.0f);
  std::vector<WorkerScratch> workers(1);
  core::TaskSystem tasks(1);
  formGroups(FormationInput{populations, rowOfId, xs, ys, vx, vy, goalState, cursor, {}},
             FormationOutput{groups, fx, fy, workers}, tasks);
  const GroupExtra& shape = groups.extraOf(groups[gid]);
  EXPECT_NEAR(shape.centroid.x, 5.05f, 1e-6f);
  EXPECT_EQ(shape.heading.x, 1.0f);
  // Same lateral place: ties go by row, so row 0 takes the right-hand slot (−y) and row 1 the left.
  EXPECT_LT(fy[0], 0.0f);
  EXPECT_GT(fy[1], 0.0f);
  EXPECT_FLOAT_EQ(fy[0], -fy[1]);
  EXPECT_GT(fx[0], 0.0f) << "the one behind closes up";
  EXPECT_LT(fx[1], 0.0f) << "the one ahead waits";
  for (std::size_t r = 0; r < 2; ++r) EXPECT_LE(std::hypot(fx[r], fy[r]), 0.5f + 1e-6f) << "capped";
}

TEST(Phases, LeadershipGoesToAMemberAndPassesToTheMostDominant) {
  // Group 0: three members with no leader yet, sociological model on with leadership changing every
  // tick; member 2 (another population) dominates. Group 1: a plain pair. Group 2: empty.
  std::vector<PopulationDesc> populations(2);
  populations[0].sociological.enabled = true;
  populations[0].sociological.leaderChangeRate = 1000.0f;  // × dt ≥ 1: a change every tick
  populations[1].sociological.domination = 0.9f;
  GroupTable groups;
  GroupState sociable, pair, empty;
  for (std::uint32_t id : {0u, 1u, 2u}) sociable.members.push_back(id);
  for (std::uint32_t id : {3u, 4u}) pair.members.push_back(id);
  empty.leader = 7;
  for (const GroupState& g : {sociable, pair, empty}) groups.markBusy(groups.add(g));
  groups.refreshBusy();
  groups[1].population = 1;  // the pair's population: no sociological model
  const std::vector<std::uint32_t> rowOfId{0, 1, 2, 3, 4};
  const std::vector<std::uint16_t> population{0, 0, 1, 1, 1};
  std::vector<Event> events;
  updateLeaders(LeaderInput{populations, 1, 0.05f, 10, rowOfId, population}, LeaderOutput{groups, events});
  EXPECT_EQ(groups[0].leader, 2u) << "the most dominant member leads";
  EXPECT_EQ(groups[1].leader, 3u) << "without the sociological model: the first member";
  EXPECT_EQ(groups[2].leader, kNoAgent) << "an empty group has no leader";
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, EventKind::LeaderChange);
  EXPECT_EQ(events[0].agent, 2u);
  EXPECT_EQ(events[0].a, 0u) << "the group";
}

TEST(Phases, SteerWalksToTheTargetSlowsBeforeAStopAndLeavesOtherRowsAlone) {
  // A 20 × 10 m room, no paths (each aims straight at its target), no neighbours, ORCA for all:
  // row 0 walks 5 m to a target it does not stop at (its population wanders), row 1 is 0.2 m from
  // its target with no goal left (it stops there), row 2 is done (no preferred velocity).
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)}, {}, nav::NavMeshConfig{});
  ASSERT_TRUE(mesh.ok());
  ScenarioDesc desc;
  desc.populations.resize(2);
  desc.populations[0].wander = true;
  for (auto& pop : desc.populations) pop.model = ModelDesc(ModelKind::Orca);  // ORCA for all
  AgentStore a;
  const std::vector<float> xs{5, 5, 5}, ys{2, 5, 8}, tx{10, 5.2f, 5}, ty{2, 5, 8};
  for (std::size_t r = 0; r < 3; ++r) {
    a.addRow();
    a.id[r] = static_cast<std::uint32_t>(r);
    a.population[r] = r == 0 ? 0 : 1;
    a.posX[r] = xs[r];
    a.posY[r] = ys[r];
    a.targetX[r] = tx[r];
    a.targetY[r] = ty[r];
    a.speed[r] = 1.2f;
    a.radius[r] = 0.25f;
    a.goalState[r] = r == 2 ? GoalState::Done : GoalState::Seeking;
  }
  a.neighbours.assign(3 * desc.steering.maxNeighbours, 0);
  a.neighbourCount.assign(3, 0);
  const OneGroup goals(3);  // an empty goal list: every row is past its last goal
  Walls walls;
  walls.build(*mesh.value(), 4.0f);
  auto orca = makeModel(ModelKind::Orca);
  orca->configure(desc);
  std::array<const OperationalModel*, kModelCount> models{};
  models[static_cast<std::size_t>(ModelKind::Orca)] = orca.get();
  std::vector<WorkerScratch> workers(1);
  workers[0].query = std::make_unique<nav::NavQuery>(mesh.value());
  workers[0].modelScratch[static_cast<std::size_t>(ModelKind::Orca)] = orca->makeScratch();
  const ModelInput model{a, walls, desc, {}, 0, {}, {}};
  core::TaskSystem tasks(1);
  const auto steerRows = [&](RowRange rows) {
    const SteerInput in{desc.steering, desc.seed, desc.populations, desc.points, a.id, a.population, a.posX, a.posY, {},
                        {}, a.speed, a.targetX, a.targetY, a.goalState, {}, a.dynamicTarget, {}, {}, a.stuckTime,
                        goals.view(), rows, models, model};
    steer(in, SteerOutput{a.prefVelX, a.prefVelY, a.corners, {a.newVelX, a.newVelY, a.holdHeading}, workers}, tasks);
  };
  // Partitioned: only row 1 is steered; the others keep what they had.
  a.prefVelX[0] = a.newVelX[0] = 9.0f;
  const std::vector<std::uint32_t> owned{1};
  steerRows(RowRange{owned.data(), 0, owned.size()});
  EXPECT_NEAR(a.prefVelX[1], 0.2f / desc.steering.arrivalTime, 1e-5f) << "slows down over arrivalTime before its stop";
  EXPECT_FLOAT_EQ(a.prefVelX[0], 9.0f);
  EXPECT_FLOAT_EQ(a.newVelX[0], 9.0f);
  // Every row.
  steerRows(RowRange{nullptr, 0, 3});
  EXPECT_FLOAT_EQ(a.prefVelX[0], 1.2f) << "full speed toward a target it walks on from";
  EXPECT_FLOAT_EQ(a.prefVelY[0], 0.0f);
  EXPECT_GT(a.newVelX[0], 0.0f) << "ORCA takes the preferred velocity up (nobody in the way)";
  EXPECT_NEAR(a.newVelY[0], 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(a.prefVelX[2], 0.0f);
  EXPECT_FLOAT_EQ(a.prefVelY[2], 0.0f);
}

TEST(Phases, EmitMergesChunksInOrderRemovesWhoExitedAndMovesTheClockOn) {
  // Three members of group 0 (leader 0) target point 0; agent 0 exited this tick (chunk 0's
  // event), agent 1 reached its goal (chunk 1's).
  test::GoalWorld w(3);
  GoalWriter goals = w.writer();
  for (std::size_t r = 0; r < 3; ++r) goals.setGoal(r, 0);
  ASSERT_EQ(w.occupied(0), 3u);
  w.events.clear();
  w.agents.goalState[0] = GoalState::Exited;
  std::vector<ChunkOutput> chunks(2);
  chunks[0].events.push_back({9, 0, EventKind::Exit, 0, 0});
  chunks[0].walkedDistance = 1.5;
  chunks[0].walkingTime = 1.0;
  chunks[0].socialMeetings = 2;
  chunks[1].events.push_back({9, 1, EventKind::GoalReached, 0, 0});
  chunks[1].walkedDistance = 0.5;
  chunks[1].walkingTime = 0.5;
  WorldStats stats;
  const EmitOutput out{chunks, w.events, stats, w.agents, w.groups, goals};
  EXPECT_TRUE(emit(EmitInput{9, 0.1f}, out)) << "a row was removed";
  ASSERT_EQ(w.events.size(), 2u);
  EXPECT_EQ(w.events[0].kind, EventKind::Exit) << "chunk order";
  EXPECT_EQ(w.events[1].kind, EventKind::GoalReached);
  EXPECT_EQ(stats.exited, 1u);
  EXPECT_DOUBLE_EQ(stats.lastExitTime, 10 * static_cast<double>(0.1f)) << "the exit counts at the end of tick 9";
  EXPECT_DOUBLE_EQ(stats.walkedDistance, 2.0);
  EXPECT_DOUBLE_EQ(stats.walkingTime, 1.5);
  EXPECT_EQ(stats.socialMeetings, 2u);
  EXPECT_EQ(stats.agentSteps, 3u) << "agents present during the tick";
  EXPECT_EQ(stats.tick, 10u);
  EXPECT_EQ(stats.active, 2u);
  for (const ChunkOutput& c : chunks) {
    EXPECT_TRUE(c.events.empty());
    EXPECT_EQ(c.walkedDistance, 0.0);
    EXPECT_EQ(c.socialMeetings, 0u);
  }
  ASSERT_EQ(w.agents.size(), 2u);
  EXPECT_EQ(w.agents.id[0], 1u);
  EXPECT_EQ(w.agents.id[1], 2u);
  EXPECT_EQ(w.groups[0].members.size(), 2u);
  EXPECT_EQ(w.groups[0].leader, 1u) << "leadership passes to the first member left";
  EXPECT_EQ(w.occupied(0), 2u) << "the exited agent's sub-region is released";
  // A tick nobody leaves: nothing removed.
  EXPECT_FALSE(emit(EmitInput{10, 0.1f}, out));
  EXPECT_EQ(stats.agentSteps, 5u);
  EXPECT_EQ(stats.tick, 11u);
}

TEST(Phases, TakeFrameHandsOverAgentsEventsSpawnsAndCommonGround) {
  test::GoalWorld w(2);
  w.agents.posX[1] = 12.0f;
  ScenarioDesc desc;
  desc.populations.resize(1);
  desc.populations[0].groups = 1;
  desc.populations[0].sizeMin = desc.populations[0].sizeMax = 2;
  Spawner spawner;
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> lists;
  spawner.addPopulation(0);
  spawner.registerGroups(desc, 0, groups, lists);
  std::vector<Event> pending{{4, 7, EventKind::GoalReached, 1, 0}};
  spawner.recordSpawn(1, 4, 0, spawner.takeAgentId(), 0, 0);
  spawner.recordSpawn(1, 4, 0, spawner.takeAgentId(), 0, 1);
  CommonGroundState commonGround;
  commonGround.pendingScript.push_back(ScriptRecord{});
  commonGround.pendingCoordinations.push_back(CoordinationRecord{});
  const FrameOutput out{spawner, pending, commonGround};
  const FramePtr frame = takeFrame(FrameInput{w.agents, 5, 0.5f, {}}, out);
  EXPECT_EQ(frame->tick, 5u);
  EXPECT_DOUBLE_EQ(frame->time, 2.5);
  EXPECT_EQ(frame->ids, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(frame->posX, (std::vector<float>{10.0f, 12.0f}));
  EXPECT_TRUE(frame->posZ.empty()) << "a flat world";
  ASSERT_EQ(frame->events.size(), 3u);
  EXPECT_EQ(frame->events[0].kind, EventKind::GoalReached);
  EXPECT_EQ(frame->events[1].kind, EventKind::Spawn) << "spawn events in place, after the event before them";
  EXPECT_EQ(frame->events[2].agent, 1u);
  EXPECT_EQ(frame->script.size(), 1u);
  EXPECT_EQ(frame->coordinations.size(), 1u);
  EXPECT_TRUE(pending.empty());
  EXPECT_TRUE(commonGround.pendingScript.empty());
  EXPECT_TRUE(commonGround.pendingCoordinations.empty());
  EXPECT_TRUE(takeFrame(FrameInput{w.agents, 6, 0.5f, {}}, out)->events.empty()) << "handed over once";
}

TEST(Phases, PlanServesPathRequestsInIdOrderWhateverTheRowOrder) {
  // 6000 agents ask at once for the way round the block; one tick's budget serves only the first
  // requests. Rows hold the ids in reverse (rows sorted spatially, row_order.cpp): the lowest ids
  // must still come first.
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)},
                                  std::vector<core::Polygon>{rect(8, 0, 12, 7)}, nav::NavMeshConfig{});
  ASSERT_TRUE(mesh.ok());
  nav::PathQueue queue(mesh.value());
  constexpr std::size_t n = 6000;
  std::vector<std::uint32_t> ids(n);
  for (std::size_t r = 0; r < n; ++r) ids[r] = static_cast<std::uint32_t>(n - 1 - r);
  const std::vector<float> xs(n, 2.0f), ys(n, 2.0f), tx(n, 18.0f), ty(n, 2.0f);
  std::vector<std::uint8_t> needPath(n, 1);
  std::vector<nav::PathTicket> tickets(n, 0);
  std::vector<CornerPath> corners(n);
  std::vector<Event> events;
  const OneGroup goals(n);
  plan(PlanInput{7, ids, {}, xs, ys, tx, ty, {}, {}, goals.view()}, PlanOutput{needPath, tickets, corners, queue, events});
  std::uint32_t servedMax = 0, waitingMin = UINT32_MAX;
  std::size_t served = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (!corners[r].empty()) {
      ++served;
      servedMax = std::max(servedMax, ids[r]);
    } else {
      waitingMin = std::min(waitingMin, ids[r]);
    }
  }
  ASSERT_GT(served, 0u);
  ASSERT_LT(served, n) << "the premise: one tick's budget does not serve everyone";
  EXPECT_LT(servedMax, waitingMin) << served << " served";
}

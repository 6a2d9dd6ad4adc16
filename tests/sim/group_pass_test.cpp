// Tests for libs/sim/src/group_pass.hpp: the group pass's serial steps called on their own through
// their contexts, on hand-built state (no World; tests/sim/goal_world.hpp).
#include "group_pass.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "goal_world.hpp"

using namespace throng;
using namespace throng::sim;

using test::GoalWorld;

namespace {

GuidanceOutput guidanceOutput(GoalWorld& w, GoalWriter& goals) {
  AgentStore& a = w.agents;
  return {w.groups, a.goalState, a.mode, a.targetX, a.targetY, a.targetZ, a.dynamicTarget, a.needPath, a.corners,
          goals, w.events};
}

bool has(const std::vector<Event>& events, EventKind kind) {
  return std::any_of(events.begin(), events.end(), [&](const Event& e) { return e.kind == kind; });
}

}  // namespace

TEST(GroupPass, CommandsGuideAndReleaseInOrder) {
  GoalWorld w(1);
  const std::vector<GroupCommand> commands{{0, true, {3, 4}, 0.0f}, {0, false, {}, 0.0f}, {0, true, {7, 2}, 1.0f}};
  applyGroupCommands(std::span(commands).first(2), w.groups);
  EXPECT_FALSE(w.groups.routeOf(w.groups[0]).guidedByApi) << "released after being guided";
  EXPECT_FLOAT_EQ(w.groups.routeOf(w.groups[0]).guide.x, 3.0f);
  applyGroupCommands(std::span(commands).subspan(2), w.groups);
  const GroupRoute& route = w.groups.routeOf(w.groups[0]);
  EXPECT_TRUE(route.guidedByApi);
  EXPECT_FLOAT_EQ(route.guide.x, 7.0f);
  EXPECT_FLOAT_EQ(route.guideHeight, 1.0f);
}

TEST(GroupPass, GuidedMembersStandAbreastBehindTheGuideThenGoBackToTheirGoal) {
  // Three members at (10, 5) heading for point 0; the API guide stands at (15, 5): the group comes
  // from the west, so its members stand `distance` west of the guide, `groupSpacing` apart along
  // perp(west) = south: the first member northmost.
  GoalWorld w(3);
  GoalWriter goals = w.writer();
  for (std::size_t r = 0; r < 3; ++r) goals.setGoal(r, 0);
  const std::vector<GroupCommand> guide{{0, true, {15, 5}, 0.0f}};
  applyGroupCommands(guide, w.groups);
  w.groups.extraOf(w.groups[0]).centroid = {10, 5};
  w.groups.refreshBusy();
  const GuidanceInput in{w.desc.populations, 0.1f, 3, w.rowOfId};
  updateGuidance(in, guidanceOutput(w, goals));
  EXPECT_TRUE(w.groups[0].guided);
  EXPECT_TRUE(has(w.events, EventKind::GuideStart));
  const PopulationDesc& pop = w.desc.populations[0];
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(w.agents.targetX[r], 15.0f - pop.guide.distance, 1e-4f) << r;
    EXPECT_NEAR(w.agents.targetY[r], 5.0f + (static_cast<float>(r) - 1.0f) * -pop.groupSpacing, 1e-4f) << r;
    EXPECT_EQ(w.agents.dynamicTarget[r], 1u);
    EXPECT_EQ(w.agents.needPath[r], 1u);
  }
  // Released: back to the group's goal (point 0), where the members drew fresh targets.
  const std::vector<GroupCommand> release{{0, false, {}, 0.0f}};
  applyGroupCommands(release, w.groups);
  updateGuidance(in, guidanceOutput(w, goals));
  EXPECT_FALSE(w.groups[0].guided);
  EXPECT_TRUE(has(w.events, EventKind::GuideEnd));
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_EQ(w.agents.dynamicTarget[r], 0u);
    EXPECT_TRUE(insideRegion(w.desc.points[0], w.agents.targetX[r], w.agents.targetY[r])) << r;
  }
  EXPECT_EQ(w.occupied(0), 3u);
}

TEST(GroupPass, AFlockingGroupWaitsForEveryMemberThenMovesOn) {
  GoalWorld w(2);
  GoalWriter goals = w.writer();
  for (std::size_t r = 0; r < 2; ++r) goals.setGoal(r, 0);
  w.groups.markBusy(0);
  w.groups.refreshBusy();
  const WaitingInput in{w.desc.populations, 0.1f, 3, w.rowOfId, w.agents.goalCursor, w.agents.goalState};
  w.agents.goalState[0] = GoalState::WaitingForGroup;
  updateWaiting(in, WaitingOutput{w.groups, goals, w.events});
  EXPECT_TRUE(w.groups.extraOf(w.groups[0]).waiting);
  EXPECT_EQ(w.groups[0].cursor, 0u) << "one of two arrived: the group waits";
  ASSERT_EQ(w.events.size(), 1u);
  EXPECT_EQ(w.events[0].kind, EventKind::GroupWaitStart);
  w.agents.goalState[1] = GoalState::WaitingForGroup;
  updateWaiting(in, WaitingOutput{w.groups, goals, w.events});
  EXPECT_EQ(w.groups[0].cursor, 1u);
  EXPECT_FALSE(w.groups.extraOf(w.groups[0]).waiting);
  EXPECT_EQ(w.events.back().kind, EventKind::GroupRelease);
  for (std::size_t r = 0; r < 2; ++r) {
    EXPECT_EQ(w.agents.goalCursor[r], 1u);
    EXPECT_EQ(w.agents.goalState[r], GoalState::Seeking);
    EXPECT_TRUE(insideRegion(w.desc.points[1], w.agents.targetX[r], w.agents.targetY[r])) << r;
  }
  EXPECT_EQ(w.occupied(0), 0u);
}

TEST(GroupPass, AFollowingGroupAdoptsTheFollowedGroupsGoalsAndCursor) {
  // Group 1 (row 1) permanently follows group 0 (row 0), which is heading for its second goal.
  GoalWorld w(1);
  w.desc.populations.push_back(w.desc.populations[0]);
  w.desc.populations[1].follow.mode = FollowMode::Permanent;
  w.goalLists.push_back({1});  // group 1's own list: point 1 only
  GroupState g;
  g.population = 1;
  g.goalList = 1;
  g.expected = 1;
  const std::uint32_t follower = w.groups.add(g);
  const std::size_t r = w.agents.addRow();
  w.agents.id[r] = 1;
  w.agents.group[r] = follower;
  w.agents.posX[r] = 10.0f;
  w.agents.posY[r] = 5.0f;
  w.agents.targetSub[r] = -1;
  w.groups[follower].members.push_back(1);
  w.groups[follower].leader = 1;
  w.rowOfId.push_back(1);
  w.groups[0].cursor = 1;
  w.groups.routeFor(follower).followGroup = 0;
  w.groups.refreshBusy();
  GoalWriter goals = w.writer();
  updateFollowing(FollowingInput{w.desc.populations, 7, 0.1f, 3, w.rowOfId, w.agents.goalState},
                  FollowingOutput{w.groups, goals, w.events});
  EXPECT_TRUE(w.groups[follower].following);
  EXPECT_EQ(w.groups[follower].cursor, 1u);
  EXPECT_EQ(w.groups.routeOf(w.groups[follower]).ownCursor, 0u);
  ASSERT_EQ(w.events.size(), 1u);
  EXPECT_EQ(w.events[0].kind, EventKind::FollowStart);
  EXPECT_EQ(w.agents.goalCursor[r], 1u);
  EXPECT_EQ(goals.view().currentGoalPoint(r), 1u) << "goal 1 of the followed group's list";
  EXPECT_TRUE(insideRegion(w.desc.points[1], w.agents.targetX[r], w.agents.targetY[r]));
}

TEST(GroupPass, ALoneDesireBecomesAVisitScriptThatStartsWalking) {
  // Common Ground on but coordination off: row 0's desire for point 1 becomes a lone visit (walk
  // there, stay, walk on); the first tick of play starts the walk.
  GoalWorld w(1, true);
  w.desc.social.enabled = true;
  w.desc.social.commonGround = false;
  w.groups.giveExtra(0);
  GoalWriter goals = w.writer();
  goals.setGoal(0, 0);
  CommonGroundState state;
  w.agents.desirePoint[0] = 1;
  w.agents.desireTrigger[0] = static_cast<std::uint8_t>(GoalTrigger::Attraction);
  w.agents.speed[0] = 1.0f;
  std::vector<ChunkOutput> chunks(1);
  chunks[0].desireRows = {0};
  const CommonGroundInput in{w.desc, 3, w.rowOfId};
  const CommonGroundOutput out{w.agents, w.groups, state, goals, w.events};
  startCoordinations(in, out, chunks);
  EXPECT_TRUE(chunks[0].desireRows.empty());
  EXPECT_EQ(w.agents.desirePoint[0], kNoPoint);
  ASSERT_EQ(state.coordinations.size(), 1u);
  const ActiveCoordination& c = state.coordinations.begin()->second;
  EXPECT_EQ(c.record.outcome, CoordinationOutcome::Alone);
  EXPECT_EQ(c.actors, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(w.agents.goalState[0], GoalState::Scripted);
  EXPECT_EQ(w.agents.coordination[0], c.record.id);
  EXPECT_EQ(w.occupied(1), 1u) << "the visit's spot is drawn in point 1's sub-regions";
  EXPECT_EQ(w.occupied(0), 0u);
  ASSERT_EQ(w.events.size(), 2u);
  EXPECT_EQ(w.events[0].kind, EventKind::GoalGenerated);
  EXPECT_EQ(w.events[1].kind, EventKind::CoordinationStart);
  runCoordinations(in, out);
  EXPECT_EQ(w.agents.scriptWalk[0], 1u) << "the first entry is the walk to the place";
  EXPECT_EQ(w.agents.needPath[0], 1u);
  EXPECT_EQ(w.agents.mode[0], AgentMode::Walking);
  EXPECT_TRUE(insideRegion(w.desc.points[1], w.agents.targetX[0], w.agents.targetY[0]));
}

TEST(GroupPass, ADividedGroupReunitesOnceItsMembersAreTogether) {
  GoalWorld w(2, true);
  w.groups.markBusy(0);
  w.groups.refreshBusy();
  w.groups.extraOf(w.groups[0]).reunite = 5;
  w.agents.posX[1] = 18.0f;  // 8 m away: not together
  CommonGroundState state;
  GoalWriter goals = w.writer();
  const CommonGroundInput in{w.desc, 3, w.rowOfId};
  const CommonGroundOutput out{w.agents, w.groups, state, goals, w.events};
  checkReunions(in, out);
  EXPECT_TRUE(w.events.empty());
  EXPECT_EQ(w.groups.extraOf(w.groups[0]).reunite, 5u);
  w.agents.posX[1] = 10.5f;
  checkReunions(in, out);
  ASSERT_EQ(w.events.size(), 1u);
  EXPECT_EQ(w.events[0].kind, EventKind::Reunited);
  EXPECT_EQ(w.events[0].b, 5u) << "names the coordination that divided it";
  EXPECT_EQ(w.groups.extraOf(w.groups[0]).reunite, kNoAgent);
}

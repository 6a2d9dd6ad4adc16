// decide — the goal state machine of every agent (parallel, each agent writes only its own row and
// its chunk's output): reaching a goal's region, stopping at action points, leaving through
// exits, asking the group pass for the next goal (goalPending) and `plan` for a path (needPath),
// noticing agents that are stuck, the Common Ground goal generator and the sociological model's
// meetings. Reads positions, targets, goal state, groups, neighbours; the serial group pass
// (groups.cpp, goals.cpp) then applies what decide asked for.
#include <algorithm>
#include <cmath>

#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Distance at which an agent counts as arrived at an action point's (or wander) target [m].
constexpr float kArriveDistance = 0.3f;
/// A guided (or following) agent that made no progress over a check period re-plans only while it is
/// farther than this from its target [m].
constexpr float kGuidedReplanDistance = 1.0f;

}  // namespace

void World::Impl::decide(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  const std::size_t grain = grainFor(n, tasks);
  chunks.resize(std::max(chunks.size(), core::TaskSystem::chunkCount(n, grain)));
  const std::uint64_t checkEvery = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(kProgressCheckPeriod / desc.dt));
  tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
    ChunkOutput& out = chunks[begin / grain];
    const nav::NavQuery& query = *worker(tasks).query;
    for (std::size_t row = begin; row < end; ++row) decideRow(row, checkEvery, out, query);
  });
  decideGroups(tasks);
}

void World::Impl::decideRow(std::size_t row, std::uint64_t checkEvery, ChunkOutput& out, const nav::NavQuery& query) {
  if (agents.coordinationOf(row) != kNoIndex) return;  // playing an action script (common_ground_play.cpp)
  const GroupState& g = groups[agents.group[row]];
  switch (agents.goalState[row]) {
    case GoalState::Exited:
    case GoalState::Done:
    case GoalState::WaitingForGroup:
    case GoalState::Scripted:  // skipped above (coordination set); listed for completeness
      break;
    case GoalState::Acting:
      if (tick >= agents.actionEndTick[row]) {
        const std::uint32_t goal = currentGoalPoint(row);
        out.events.push_back({tick, agents.id[row], EventKind::ActionEnd, goal == kNoPoint ? 0 : goal, 0});
        reachGoal(row, g, out);
      }
      break;
    case GoalState::Seeking:
      // Guided groups and agents following another agent get their targets from the group pass.
      if (g.guided || agents.followedAgent(row) != kNoAgent) {
        checkProgress(row, checkEvery, kGuidedReplanDistance);
      } else {
        seekGoal(row, g, checkEvery, out);
      }
      break;
  }
  // Common Ground goal generator: needs and places in view.
  if (agents.goalState[row] == GoalState::Seeking && desc.social.enabled) generateGoal(row, out, query);
  if (agents.sociological) agents.sociologicalEffect[row] = SocialEffect::None;
  const PopulationDesc& pop = desc.populations[g.population];
  if (pop.sociological.enabled && agents.goalState[row] == GoalState::Seeking && agents.followAgent[row] == kNoAgent &&
      !g.guided) {
    meetOthers(row, pop.sociological, out);
  }
}

void World::Impl::reachGoal(std::size_t row, const GroupState& g, ChunkOutput& out) {
  // Flocking rule 4: a member that reached the group's goal waits there for the others.
  if (g.flocks(desc.populations[g.population]) && g.members.size() >= 2 && agents.goalCursor[row] == g.cursor) {
    agents.goalState[row] = GoalState::WaitingForGroup;
    agents.mode[row] = AgentMode::Waiting;
    agents.targetSelf(row);
    agents.corners[row].clear();
  } else {
    agents.goalPending[row] = GoalPending::NextGoal;  // the group pass moves it on (target draws are serial)
    out.pendingRows.push_back(static_cast<std::uint32_t>(row));
  }
}

void World::Impl::checkProgress(std::size_t row, std::uint64_t checkEvery, float minDistance) {
  // An agent that got no closer to its target over a check period re-plans from where it stands
  // (agents within minDistance of their target, standing at their place, never do).
  if ((tick + agents.id[row]) % checkEvery != 0 || agents.ticket[row] != 0) return;
  const float dx = agents.targetX[row] - agents.posX[row], dy = agents.targetY[row] - agents.posY[row];
  const float d = std::sqrt(dx * dx + dy * dy);
  if (d > minDistance && d > agents.progressDistance[row] - 0.5f) agents.needPath[row] = 1;
  agents.progressDistance[row] = d;
}

void World::Impl::seekGoal(std::size_t row, const GroupState& g, std::uint64_t checkEvery, ChunkOutput& out) {
  const PopulationDesc& pop = desc.populations[g.population];
  const std::uint32_t pointIndex = currentGoalPoint(row);
  const float x = agents.posX[row], y = agents.posY[row];
  if (pointIndex == kNoPoint) {  // wandering
    const float dx = agents.targetX[row] - x, dy = agents.targetY[row] - y;
    // A flocking group wanders to one shared point: close enough is within the group's width.
    const bool together = g.flocks(pop) && g.members.size() >= 2;
    const float reach = together ? kArriveDistance + pop.groupSpacing * static_cast<float>(g.members.size())
                                 : std::sqrt(kArriveDistance * kArriveDistance + agents.radius[row] * agents.radius[row]);
    if (dx * dx + dy * dy < reach * reach && agents.sameLevel(row, agents.targetHeight(row))) {
      if (together && agents.goalCursor[row] == g.cursor) {
        agents.goalState[row] = GoalState::WaitingForGroup;  // released together, to a new point
        agents.mode[row] = AgentMode::Waiting;
      } else {
        agents.goalPending[row] = GoalPending::NextWanderTarget;  // the group pass draws the next random target
        out.pendingRows.push_back(static_cast<std::uint32_t>(row));
      }
    }
    return;
  }
  const PointDesc& point = desc.points[pointIndex];
  bool arrived;
  if (point.kind == PointKind::Action && point.stop) {
    const float dx = agents.targetX[row] - x, dy = agents.targetY[row] - y;
    arrived = dx * dx + dy * dy < kArriveDistance * kArriveDistance && agents.sameLevel(row, agents.targetHeight(row));
  } else {
    arrived = insideRegion(point, x, y) && agents.sameLevel(row, point.height);
  }
  if (!arrived) {
    checkProgress(row, checkEvery, -1e30f);
    return;
  }
  const std::uint32_t id = agents.id[row];
  if (point.kind == PointKind::Exit) {
    agents.goalState[row] = GoalState::Exited;
    out.events.push_back({tick, id, EventKind::Exit, pointIndex, 0});
  } else if (point.kind == PointKind::Action && point.stop && point.actionDuration > 0.0f) {
    agents.goalState[row] = GoalState::Acting;
    agents.mode[row] = AgentMode::Acting;
    agents.actionEndTick[row] = static_cast<std::uint32_t>(tick + static_cast<std::uint64_t>(std::lround(point.actionDuration / desc.dt)));
    agents.oriX[row] = point.orientation.x;
    agents.oriY[row] = point.orientation.y;
    out.events.push_back({tick, id, EventKind::ActionStart, pointIndex, 0});
  } else {
    out.events.push_back({tick, id, EventKind::GoalReached, pointIndex, 0});
    reachGoal(row, g, out);
  }
}

void World::Impl::meetOthers(std::size_t row, const SociologicalDesc& social, ChunkOutput& out) {
  // Sociological model (Musse et al. §3.2.1 iii): meeting an agent of another group may make this
  // one join that group or follow that agent for a while (rates per second, one draw per meeting
  // pair and tick). Neighbours come nearest first.
  const std::size_t k = desc.steering.maxNeighbours;
  const std::uint32_t* nb = &agents.neighbours[row * k];
  const std::uint32_t id = agents.id[row];
  for (std::size_t i = 0; i < agents.neighbourCount[row]; ++i) {
    const std::uint32_t o = nb[i];
    if (agents.group[o] == agents.group[row]) continue;
    const float dx = agents.posX[o] - agents.posX[row], dy = agents.posY[o] - agents.posY[row];
    if (dx * dx + dy * dy > social.meetDistance * social.meetDistance) break;
    ++out.socialMeetings;
    core::Rng rng(desc.seed, core::mix64((static_cast<std::uint64_t>(id) << 32) ^ agents.id[o]) ^ tick,
                  core::RngPurpose::Behaviour);
    const double u = rng.uniform();
    const double pJoin = social.changeGroupRate * social.sociability * desc.dt;
    const double pFollow = social.followAgentRate * social.sociability * desc.dt;
    if (u < pJoin) {
      agents.sociologicalEffect[row] = SocialEffect::JoinGroup;
    } else if (u < pJoin + pFollow) {
      agents.sociologicalEffect[row] = SocialEffect::FollowAgent;
    }
    if (agents.sociologicalEffect[row] != SocialEffect::None) {
      agents.sociologicalOther[row] = agents.id[o];
      break;
    }
  }
}

}  // namespace throng::sim

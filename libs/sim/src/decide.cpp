// decide — the goal state machine of every agent (parallel, each agent writes only its own row and
// its chunk's event list): reaching a goal's region, stopping at action points, leaving through
// exits, drawing the next target, asking `plan` for a path, and noticing agents that are stuck.
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

void World::Impl::releaseTarget(std::size_t row) {
  if (agents.targetSub[row] >= 0) {
    --subOccupancy[static_cast<std::size_t>(agents.targetSub[row])];
    agents.targetSub[row] = -1;
  }
}

core::Vec2 World::Impl::drawTarget(std::size_t row, const PointDesc& point, const nav::NavQuery& query) {
  // Sub-regions (Musse et al. §3.1.3): the target lies in a sub-region of the goal's region picked
  // by proximity and by how many agents already target it, so group members take similar but never
  // identical paths and spread over the region. Serial (group pass / spawning): occupancy is shared.
  core::Rng rng(desc.seed, (static_cast<std::uint64_t>(agents.id[row]) << 20) ^ agents.targetDraws[row]++,
                core::RngPurpose::Target);
  releaseTarget(row);
  const auto p = static_cast<std::size_t>(&point - desc.points.data());
  const std::uint32_t first = subOffset[p], last = subOffset[p + 1];
  core::Vec2 target = point.position;
  if (last > first) {
    const std::span<const crowd::Subregion> subs(subregions.data() + first, last - first);
    const std::span<const std::uint32_t> occupancy(subOccupancy.data() + first, last - first);
    const std::size_t k = crowd::pickSubregion(subs, core::Vec2{agents.posX[row], agents.posY[row]}, occupancy, rng);
    target = crowd::samplePoint(subs[k], rng);
    agents.targetSub[row] = static_cast<std::int32_t>(first + k);
    ++subOccupancy[first + k];
  }
  if (agents.levels) {
    // Multi-level world: the point's height picks the floor the target is snapped onto.
    auto hit = query.snap(target, point.height, 3.0f);
    if (!hit) hit = query.snap(point.position, point.height, 10.0f);
    agents.setTargetHeight(row, hit ? hit->height : point.height);
    return hit ? hit->p : target;
  }
  if (auto hit = query.nearest(target, 3.0f)) return hit->first;
  if (auto hit = query.nearest(point.position, 10.0f)) return hit->first;
  return target;
}

void World::Impl::advanceGoal(std::size_t row, const nav::NavQuery& query) {
  setGoal(row, agents.goalCursor[row] + 1, query);
}

void World::Impl::setGoal(std::size_t row, std::uint32_t cursor, const nav::NavQuery& query) {
  const GroupState& g = groups[agents.group[row]];
  const PopulationDesc& pop = desc.populations[g.population];
  const std::vector<std::uint32_t>& goals = activeGoals(g);
  agents.goalCursor[row] = cursor;
  agents.ticket[row] = 0;  // a path still queued for the old goal expires unread
  agents.dynamicTarget[row] = 0;
  agents.corners[row].clear();
  agents.progressDistance[row] = 1e30f;
  if (cursor < goals.size()) {
    const core::Vec2 t = drawTarget(row, desc.points[goals[cursor]], query);
    agents.targetX[row] = t.x;
    agents.targetY[row] = t.y;
    agents.needPath[row] = 1;
    agents.goalState[row] = GoalState::Seeking;
    agents.mode[row] = AgentMode::Walking;
    if (pop.bezierPaths) bezierPath(row, query);
  } else if (pop.wander) {
    // Random points of the walkable area; a flocking group shares one per release (its cursor).
    const bool together = g.flocks(pop) && g.expected >= 2;
    const std::uint32_t gid = agents.group[row];
    core::Rng rng = together ? core::Rng(desc.seed, (static_cast<std::uint64_t>(gid) << 32) ^ cursor ^ 0x5a5a0000u, core::RngPurpose::Goal)
                             : core::Rng(desc.seed, (static_cast<std::uint64_t>(agents.id[row]) << 20) ^ agents.targetDraws[row]++,
                                         core::RngPurpose::Goal);
    releaseTarget(row);
    const float r0 = static_cast<float>(rng.uniform()), r1 = static_cast<float>(rng.uniform()),
                r2 = static_cast<float>(rng.uniform());
    if (agents.levels) {
      const auto p = query.randomMeshPoint(r0, r1, r2);
      if (p) {
        agents.targetX[row] = p->p.x;
        agents.targetY[row] = p->p.y;
        agents.targetZ[row] = p->height;
      } else {
        agents.targetSelf(row);
      }
    } else {
      const auto p = query.randomPoint(r0, r1, r2);
      agents.targetX[row] = p ? p->x : agents.posX[row];
      agents.targetY[row] = p ? p->y : agents.posY[row];
    }
    agents.needPath[row] = 1;
    agents.goalState[row] = GoalState::Seeking;
    agents.mode[row] = AgentMode::Walking;
  } else {
    releaseTarget(row);
    agents.goalState[row] = GoalState::Done;
    agents.mode[row] = AgentMode::Waiting;
    agents.targetSelf(row);
  }
}

void World::Impl::decide(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  const std::size_t grain = grainFor(n, tasks);
  chunks.resize(std::max(chunks.size(), core::TaskSystem::chunkCount(n, grain)));
  const std::uint64_t checkEvery = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(kProgressCheckPeriod / desc.dt));
  const std::size_t k = desc.steering.maxNeighbours;
  tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
    ChunkOutput& out = chunks[begin / grain];
    const nav::NavQuery& query = *worker(tasks).query;
    for (std::size_t row = begin; row < end; ++row) {
      if (agents.coordinationOf(row) != kNoAgent) continue;  // playing an action script (social.cpp)
      const std::uint32_t id = agents.id[row];
      const GroupState& g = groups[agents.group[row]];
      const PopulationDesc& pop = desc.populations[g.population];
      const std::vector<std::uint32_t>& goals = activeGoals(g);
      // Flocking rule 4: a member that reached the group's goal waits there for the others.
      auto arrive = [&](std::uint32_t pointIndex) {
        if (g.flocks(pop) && g.members.size() >= 2 && agents.goalCursor[row] == g.cursor) {
          agents.goalState[row] = GoalState::WaitingForGroup;
          agents.mode[row] = AgentMode::Waiting;
          agents.targetSelf(row);
          agents.corners[row].clear();
          (void)pointIndex;
        } else {
          agents.goalPending[row] = 1;  // the group pass moves it on (target draws are serial)
          out.pendingRows.push_back(static_cast<std::uint32_t>(row));
        }
      };
      switch (agents.goalState[row]) {
        case GoalState::Exited:
        case GoalState::Done:
        case GoalState::WaitingForGroup:
        case GoalState::Scripted:  // skipped above (coordination set); listed for completeness
          break;
        case GoalState::Acting:
          if (tick >= agents.actionEndTick[row]) {
            const std::uint32_t point = agents.goalCursor[row] < goals.size() ? goals[agents.goalCursor[row]] : 0;
            out.events.push_back({tick, id, EventKind::ActionEnd, point, 0});
            arrive(point);
          }
          break;
        case GoalState::Seeking: {
          // Guided groups and agents following another agent get their targets from the group pass.
          if (g.guided || agents.followedAgent(row) != kNoAgent) {
            // Their path is re-planned when the guide (or the one followed) moves on; one that got
            // stuck on the way (a corner it cannot round) asks again from where it stands.
            // The same progress check as below, for agents still more than kGuidedReplanDistance
            // from their target (members standing at their place beside the guide never re-plan).
            if ((tick + id) % checkEvery == 0 && agents.ticket[row] == 0) {
              const float dx = agents.targetX[row] - agents.posX[row], dy = agents.targetY[row] - agents.posY[row];
              const float d = std::sqrt(dx * dx + dy * dy);
              if (d > kGuidedReplanDistance && d > agents.progressDistance[row] - 0.5f) agents.needPath[row] = 1;
              agents.progressDistance[row] = d;
            }
            break;
          }
          const float x = agents.posX[row], y = agents.posY[row];
          if (agents.goalCursor[row] >= goals.size()) {  // wandering
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
                agents.goalPending[row] = 2;  // the group pass draws the next random target
                out.pendingRows.push_back(static_cast<std::uint32_t>(row));
              }
            }
            break;
          }
          const std::uint32_t pointIndex = goals[agents.goalCursor[row]];
          const PointDesc& point = desc.points[pointIndex];
          bool arrived;
          if (point.kind == PointKind::Action && point.stop) {
            const float dx = agents.targetX[row] - x, dy = agents.targetY[row] - y;
            arrived = dx * dx + dy * dy < kArriveDistance * kArriveDistance && agents.sameLevel(row, agents.targetHeight(row));
          } else {
            arrived = insideRegion(point, x, y) && agents.sameLevel(row, point.height);
          }
          if (arrived) {
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
              arrive(pointIndex);
            }
            break;
          }
          // Progress check: an agent that got no closer over a period re-plans from where it is.
          if ((tick + id) % checkEvery == 0 && agents.ticket[row] == 0) {
            const float d = std::sqrt((agents.targetX[row] - x) * (agents.targetX[row] - x) +
                                      (agents.targetY[row] - y) * (agents.targetY[row] - y));
            if (d > agents.progressDistance[row] - 0.5f) agents.needPath[row] = 1;
            agents.progressDistance[row] = d;
          }
          break;
        }
      }
      // Common Ground goal generator: needs and places in view.
      if (agents.goalState[row] == GoalState::Seeking && desc.social.enabled) generateGoal(row, out, query);
      // Sociological model: meeting an agent of another group may make this one join that group
      // or follow that agent for a while (rates per second, one draw per meeting pair and tick).
      if (agents.sociological) agents.socialEffect[row] = 0;
      const SociologicalDesc& social = pop.sociological;
      if (social.enabled && agents.goalState[row] == GoalState::Seeking && agents.followAgent[row] == kNoAgent &&
          !g.guided) {
        const std::uint32_t* nb = &agents.neighbours[row * k];
        for (std::size_t i = 0; i < agents.neighbourCount[row]; ++i) {
          const std::uint32_t o = nb[i];
          if (agents.group[o] == agents.group[row]) continue;
          const float dx = agents.posX[o] - agents.posX[row], dy = agents.posY[o] - agents.posY[row];
          if (dx * dx + dy * dy > social.meetDistance * social.meetDistance) break;  // nearest first
          ++out.socialMeetings;
          core::Rng rng(desc.seed, core::mix64((static_cast<std::uint64_t>(id) << 32) ^ agents.id[o]) ^ tick,
                        core::RngPurpose::Behaviour);
          const double u = rng.uniform();
          const double pJoin = social.changeGroupRate * social.sociability * desc.dt;
          const double pFollow = social.followAgentRate * social.sociability * desc.dt;
          if (u < pJoin) {
            agents.socialEffect[row] = 1;
          } else if (u < pJoin + pFollow) {
            agents.socialEffect[row] = 2;
          }
          if (agents.socialEffect[row] != 0) {
            agents.socialOther[row] = agents.id[o];
            break;
          }
        }
      }
    }
  });
  decideGroups(tasks);
}

}  // namespace throng::sim

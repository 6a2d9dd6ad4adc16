// decide — the goal state machine of every agent (parallel, each agent writes only its own row and
// its chunk's output): reaching a goal's region, stopping at action points (or next to one, behind
// the people already there: inAudience), leaving through
// exits (not through one the timeline has closed), asking the group pass for the next goal (goalPending) and `plan` for a path (needPath),
// noticing agents that are stuck, the end of an agent's pre-movement time, the Common Ground goal
// generator and the sociological model's meetings. Reads DecideInput (positions, targets, groups, goals, neighbours, …); writes
// DecideOutput (phases.hpp): goal state, mode, target, the flags for plan and the group pass, and
// chunk events. The serial group pass (groups.cpp, goals.cpp) then applies what decide asked for.
// Also here: insideRegion, the test of a point's region.
#include <algorithm>
#include <cmath>

#include "phases.hpp"
#include "vertical_transport.hpp"
#include "throng/core/assert.hpp"

namespace throng::sim {
namespace {

/// Distance at which an agent counts as arrived at an action point's (or wander) target [m].
constexpr float kArriveDistance = 0.3f;
/// An audience: a walker held up this long [s] (stuck) or walking slower than a quarter of its
/// desired speed within kAudienceMargin [m] of an action point's area (people standing there
/// between it and its spot) starts the action where it stands, as people at
/// the back of a crowd round a fountain or a street performer watch from there (Still 2000, "Crowd
/// dynamics", ch. 6, crowds round attractions). Common Ground's script walks arrive the same way.
constexpr float kAudienceWait = 1.5f;
constexpr float kAudienceMargin = 1.0f;
/// A guided (or following) agent that made no progress over a check period re-plans only while it is
/// farther than this from its target [m].
constexpr float kGuidedReplanDistance = 1.0f;

/// One agent's decision this tick: its row, the world it reads, where it writes.
struct RowDecision {
  const DecideInput& in;
  const DecideOutput& out;
  std::uint64_t checkEvery;  ///< ticks between progress checks
  std::uint64_t sightEvery;  ///< ticks between an off-course agent's looks for its corner (kSightCheckPeriod)
  ChunkOutput& chunk;
  const nav::NavQuery& query;  ///< this worker's (the goal generator's line of sight)
  std::size_t row;

  [[nodiscard]] float targetHeight() const { return out.targetZ.empty() ? 0.0f : out.targetZ[row]; }
  /// Squared horizontal distance to the target [m²].
  [[nodiscard]] float targetDistanceSq() const {
    const float dx = out.targetX[row] - in.agents.posX[row], dy = out.targetY[row] - in.agents.posY[row];
    return dx * dx + dy * dy;
  }
  /// Held up next to an action point's area (kAudienceWait, kAudienceMargin).
  [[nodiscard]] bool inAudience(const PointDesc& point) const {
    const float vx = in.agents.velX[row], vy = in.agents.velY[row];
    const float slow = 0.25f * in.agents.speed[row];
    if (in.agents.stuckTime[row] < kAudienceWait && vx * vx + vy * vy > slow * slow) return false;
    const float dx = point.position.x - in.agents.posX[row], dy = point.position.y - in.agents.posY[row];
    const float reach = point.radius + kAudienceMargin;
    return dx * dx + dy * dy < reach * reach;
  }
  void wait() {
    out.goalState[row] = GoalState::WaitingForGroup;
    out.mode[row] = AgentMode::Waiting;
  }
  void flag(GoalPending pending) {
    out.goalPending[row] = pending;  // the group pass moves it on (target draws are serial)
    chunk.pendingRows.push_back(static_cast<std::uint32_t>(row));
  }
  void event(EventKind kind, std::uint32_t point) { chunk.events.push_back({in.tick, in.agents.id[row], kind, point, 0}); }

  void decideRow();
  void breathe();
  void incapacitate();
  void seekGoal(const GroupState& g);
  void seekWanderTarget(const GroupState& g);
  void reachGoal(const GroupState& g);
  void checkProgress(float minDistance);
  void checkSight();
  void checkFloor();
  void meetOthers(const SociologicalDesc& social);
};

void RowDecision::decideRow() {
  const AgentStore& a = in.agents;
  breathe();
  if (a.coordinationOf(row) != kNoIndex) return;  // playing an action script (common_ground_play.cpp)
  const GroupState& g = in.groups[a.group[row]];
  if (!out.dose.empty() && out.goalState[row] != GoalState::Exited && out.goalState[row] != GoalState::Incapacitated &&
      out.goalState[row] != GoalState::Riding &&
      out.dose[row] >= in.desc.populations[a.population[row]].incapacitationDose) {
    incapacitate();
  }
  switch (out.goalState[row]) {
    case GoalState::Exited:
    case GoalState::Done:
    case GoalState::Incapacitated:
    case GoalState::WaitingForGroup:
    case GoalState::Scripted:  // skipped above (coordination set); listed for completeness
    case GoalState::Riding:    // queuing at or carried by a lift or escalator (vertical_transport.cpp)
      break;
    case GoalState::Acting:
      if (in.tick >= out.actionEndTick[row]) {
        const std::uint32_t goal = in.goals.currentGoalPoint(row);
        event(EventKind::ActionEnd, goal == kNoPoint ? 0 : goal);
        reachGoal(g);
      }
      break;
    case GoalState::PreMovement:
      // Its pre-movement time is over: it walks off (its target and path were set when it appeared).
      if (in.tick >= out.actionEndTick[row]) {
        out.goalState[row] = GoalState::Seeking;
        out.mode[row] = AgentMode::Walking;
      }
      break;
    case GoalState::Seeking:
      // Guided groups and agents following another agent get their targets from the group pass.
      if (g.guided || a.followedAgent(row) != kNoAgent) {
        checkProgress(kGuidedReplanDistance);
      } else {
        seekGoal(g);
      }
      break;
  }
  // Common Ground goal generator: needs and places in view.
  if (out.goalState[row] == GoalState::Seeking && in.desc.social.enabled) {
    generateGoal(in, out, row, chunk, query);
  }
  if (a.sociological) out.sociologicalEffect[row] = SocialEffect::None;
  const PopulationDesc& pop = in.desc.populations[g.population];
  if (pop.sociological.enabled && out.goalState[row] == GoalState::Seeking && a.followAgent[row] == kNoAgent &&
      !g.guided) {
    meetOthers(pop.sociological);
  }
}

void RowDecision::breathe() {
  // Smoke's carbon monoxide (SmokeDesc::co): the dose taken up over this tick, from the most toxic
  // region the agent stands in (ISO 13571's FED: coDosePerSecond), whatever it is doing — walking,
  // acting, waiting, in a script, incapacitated — until it is out.
  if (out.dose.empty() || out.goalState[row] == GoalState::Exited) return;
  float ppm = 0.0f;
  const core::Vec2 pos{in.agents.posX[row], in.agents.posY[row]};
  for (const SmokeDesc& smoke : in.desc.smoke) {
    if (smoke.co > ppm && core::pointInPolygon(smoke.polygon, pos)) ppm = smoke.co;
  }
  if (ppm > 0.0f) out.dose[row] += coDosePerSecond(ppm) * in.desc.dt;
}

void RowDecision::incapacitate() {
  // Its dose reached its population's incapacitationDose: it stops where it is, for good (groups,
  // guides, exit choice and Common Ground leave it alone: holdsOwnTarget), an obstacle to others.
  out.goalState[row] = GoalState::Incapacitated;
  out.mode[row] = AgentMode::Waiting;
  out.targetX[row] = in.agents.posX[row];
  out.targetY[row] = in.agents.posY[row];
  if (!out.targetZ.empty()) out.targetZ[row] = in.agents.posZ[row];
  out.corners[row].clear();
  out.needPath[row] = 0;
  event(EventKind::Incapacitated, static_cast<std::uint32_t>(std::lround(std::min(out.dose[row], 4.0e6f) * 1000.0f)));
}

void RowDecision::reachGoal(const GroupState& g) {
  // Flocking rule 4: a member that reached the group's goal waits there for the others.
  if (g.flocks(in.desc.populations[g.population]) && g.members.size() >= 2 && in.agents.goalCursor[row] == g.cursor) {
    wait();
    out.targetX[row] = in.agents.posX[row];  // the target is where it stands
    out.targetY[row] = in.agents.posY[row];
    if (!out.targetZ.empty()) out.targetZ[row] = in.agents.posZ[row];
    out.corners[row].clear();
  } else {
    flag(GoalPending::NextGoal);
  }
}

void RowDecision::checkProgress(float minDistance) {
  // An agent that got no closer to its target over a check period re-plans from where it stands
  // (agents within minDistance of their target, standing at their place, never do).
  if ((in.tick + in.agents.id[row]) % checkEvery != 0 || in.agents.ticket[row] != 0) return;
  const float d = std::sqrt(targetDistanceSq());
  if (d > minDistance && d > out.progressDistance[row] - 0.5f) out.needPath[row] = 1;
  out.progressDistance[row] = d;
}

void RowDecision::checkSight() {
  // Pushed out of sight of the corner it walks to — someone who had seen past a door's jamb, pushed
  // back behind the wall by the crowd at the door — an agent walks into the wall and the navmesh
  // slides it along, away from the door, until the progress check. So an agent whose last step did
  // not head for its corner (within about 30°) looks for it, every kSightCheckPeriod, and re-plans
  // from where it stands if it cannot see it (flat worlds; docs/crowd-model.md, the dense room).
  const AgentStore& a = in.agents;
  if (a.levels || a.ticket[row] != 0 || out.needPath[row] != 0) return;
  if ((in.tick + a.id[row]) % sightEvery != 0) return;
  const CornerPath& corners = a.corners[row];
  const core::Vec2 pos{a.posX[row], a.posY[row]};
  const core::Vec2 aim = corners.index < corners.size() ? corners[corners.index] : core::Vec2{a.targetX[row], a.targetY[row]};
  if (!onCourse({a.velX[row], a.velY[row]}, aim - pos) && !query.visible(pos, aim)) out.needPath[row] = 1;
}

void RowDecision::checkFloor() {
  // Multi-level worlds: corners are followed in the plane, so a walker pushed off a stair onto the
  // floor it runs over walked on the wrong floor to the point under the stair's top and on, until
  // it stood and was found stuck (docs/crowd-model.md, the department store). The path's corners
  // carry their floors' heights (plan): an agent more than kSameLevel off the height its path has
  // where it stands — between the corner passed and the one it walks to, or at the first corner
  // that corner's — re-plans from where it is, every kSightCheckPeriod.
  const AgentStore& a = in.agents;
  if (!a.levels || a.ticket[row] != 0 || out.needPath[row] != 0) return;
  if ((in.tick + a.id[row]) % sightEvery != 0) return;
  const CornerPath& corners = a.corners[row];
  const std::uint32_t ci = corners.index;
  if (ci >= corners.size()) return;
  const float at = a.cornerHeight(row, ci);
  if (std::isnan(at)) return;
  const core::Vec2 pos{a.posX[row], a.posY[row]};
  float expected = at;
  if (ci > 0) {
    const core::Vec2 from = corners[ci - 1], leg = corners[ci] - from;
    const float len2 = core::lengthSq(leg);
    const float t = len2 > 1e-8f ? std::clamp(core::dot(pos - from, leg) / len2, 0.0f, 1.0f) : 1.0f;
    const float before = a.cornerHeight(row, ci - 1);
    expected = before + (at - before) * t;
  } else {
    const float reach = in.desc.steering.cornerReach;
    if (core::lengthSq(corners[0] - pos) >= reach * reach) return;  // the first leg: at its corner only
  }
  if (std::abs(a.posZ[row] - expected) >= AgentStore::kSameLevel) out.needPath[row] = 1;
}

void RowDecision::seekWanderTarget(const GroupState& g) {
  const PopulationDesc& pop = in.desc.populations[g.population];
  // A flocking group wanders to one shared point: close enough is within the group's width.
  const bool together = g.flocks(pop) && g.members.size() >= 2;
  const float radius = in.agents.radius[row];
  const float reach = together ? kArriveDistance + pop.groupSpacing * static_cast<float>(g.members.size())
                               : std::sqrt(kArriveDistance * kArriveDistance + radius * radius);
  if (targetDistanceSq() < reach * reach && in.agents.sameLevel(row, targetHeight())) {
    if (together && in.agents.goalCursor[row] == g.cursor) {
      wait();  // released together, to a new point
    } else {
      flag(GoalPending::NextWanderTarget);  // the group pass draws the next random target
    }
  }
}

void RowDecision::seekGoal(const GroupState& g) {
  const std::uint32_t pointIndex = in.goals.currentGoalPoint(row);
  if (pointIndex == kNoPoint) {
    seekWanderTarget(g);
    return;
  }
  const PointDesc& point = in.desc.points[pointIndex];
  bool arrived;
  if (point.kind == PointKind::Action && point.stop) {
    arrived = (targetDistanceSq() < kArriveDistance * kArriveDistance || inAudience(point)) &&
              in.agents.sameLevel(row, targetHeight());
  } else {
    arrived = insideRegion(point, in.agents.posX[row], in.agents.posY[row]) && in.agents.sameLevel(row, point.height);
  }
  if (!arrived) {
    checkSight();
    checkFloor();
    checkProgress(-1e30f);
    return;
  }
  if (const std::uint32_t t = in.desc.transports.empty() ? kNoIndex : VerticalTransports::boardingAt(in.desc, pointIndex);
      t != kNoIndex) {
    // A lift's or escalator's stop: it queues there and is carried (vertical_transport.cpp). For a lift it
    // waits in the lobby where it stands; for an escalator it creeps on toward where people step on
    // (the point's position; steer.cpp, kQueueSpeed).
    const bool creeps = in.desc.transports[t].kind == TransportKind::Escalator;
    out.goalState[row] = GoalState::Riding;
    out.mode[row] = creeps ? AgentMode::Walking : AgentMode::Waiting;
    out.targetX[row] = creeps ? point.position.x : in.agents.posX[row];
    out.targetY[row] = creeps ? point.position.y : in.agents.posY[row];
    if (!out.targetZ.empty()) out.targetZ[row] = creeps ? point.height : in.agents.posZ[row];
    out.corners[row].clear();
    out.needPath[row] = creeps ? 1 : 0;
    event(EventKind::GoalReached, pointIndex);
  } else if (point.kind == PointKind::Exit) {
    // A closed door lets nobody through: the agent waits in front of it until it opens (or, with
    // exit choice, until its group picks an open exit).
    if (pointIndex < in.closedExits.size() && in.closedExits[pointIndex] != 0) return;
    out.goalState[row] = GoalState::Exited;
    event(EventKind::Exit, pointIndex);
  } else if (point.kind == PointKind::Action && point.stop && point.actionDuration > 0.0f) {
    out.goalState[row] = GoalState::Acting;
    out.mode[row] = AgentMode::Acting;
    out.actionEndTick[row] = static_cast<std::uint32_t>(in.tick + static_cast<std::uint64_t>(std::lround(point.actionDuration / in.desc.dt)));
    out.oriX[row] = point.orientation.x;
    out.oriY[row] = point.orientation.y;
    event(EventKind::ActionStart, pointIndex);
  } else {
    event(EventKind::GoalReached, pointIndex);
    reachGoal(g);
  }
}

void RowDecision::meetOthers(const SociologicalDesc& social) {
  // Sociological model (Musse et al. §3.2.1 iii): meeting an agent of another group may make this
  // one join that group or follow that agent for a while (rates per second, one draw per meeting
  // pair and tick). Neighbours come nearest first.
  const AgentStore& a = in.agents;
  const std::size_t k = in.desc.steering.maxNeighbours;
  const std::uint32_t* nb = &a.neighbours[row * k];
  const std::uint32_t id = a.id[row];
  for (std::size_t i = 0; i < a.neighbourCount[row]; ++i) {
    const std::uint32_t o = nb[i];
    if (a.group[o] == a.group[row]) continue;
    const float dx = a.posX[o] - a.posX[row], dy = a.posY[o] - a.posY[row];
    if (dx * dx + dy * dy > social.meetDistance * social.meetDistance) break;
    ++chunk.socialMeetings;
    core::Rng rng(in.desc.seed, core::mix64((static_cast<std::uint64_t>(id) << 32) ^ a.id[o]) ^ in.tick,
                  core::RngPurpose::Behaviour);
    const double u = rng.uniform();
    const double pJoin = social.changeGroupRate * social.sociability * in.desc.dt;
    const double pFollow = social.followAgentRate * social.sociability * in.desc.dt;
    if (u < pJoin) {
      out.sociologicalEffect[row] = SocialEffect::JoinGroup;
    } else if (u < pJoin + pFollow) {
      out.sociologicalEffect[row] = SocialEffect::FollowAgent;
    }
    if (out.sociologicalEffect[row] != SocialEffect::None) {
      out.sociologicalOther[row] = a.id[o];
      break;
    }
  }
}

/// How deep the bodies (discs) of rows [begin, end) overlap their neighbours: the deepest, and how
/// many overlap one by more than kOverlapReported (WorldStats, reported by `throng run`).
void measureOverlaps(const AgentStore& a, std::size_t k, std::size_t begin, std::size_t end, ChunkOutput& chunk) {
  end = std::min(end, a.neighbourCount.size());  // no neighbour lists (a phase run on its own): nothing to measure
  for (std::size_t row = begin; row < end; ++row) {
    float deepest = 0.0f;
    const std::uint32_t* nb = &a.neighbours[row * k];
    for (std::size_t n = 0; n < a.neighbourCount[row]; ++n) {
      const std::uint32_t o = nb[n];
      const float dx = a.posX[o] - a.posX[row], dy = a.posY[o] - a.posY[row];
      const float l = a.radius[row] + a.radius[o], d2 = dx * dx + dy * dy;
      if (d2 < l * l) deepest = std::max(deepest, l - std::sqrt(d2));  // the square root only for overlaps
    }
    chunk.maxOverlap = std::max(chunk.maxOverlap, deepest);
    if (deepest > kOverlapReported) ++chunk.overlapping;
  }
}

}  // namespace

void decide(const DecideInput& in, const DecideOutput& out, const core::TaskSystem& tasks) {
  const std::size_t n = in.agents.size();
  const std::size_t grain = phaseGrain(n, tasks);
  const std::uint64_t checkEvery = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(kProgressCheckPeriod / in.desc.dt));
  const std::uint64_t sightEvery = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(kSightCheckPeriod / in.desc.dt));
  tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
    ChunkOutput& chunk = out.chunks[begin / grain];
    const auto worker = static_cast<std::size_t>(tasks.workerIndex());
    THRONG_ASSERT(worker < in.workers.size());
    const nav::NavQuery& query = *in.workers[worker].query;
    for (std::size_t row = begin; row < end; ++row) {
      // Rows sorted spatially (row_order.cpp) read their groups in no particular order: fetch ahead.
      if (row + kGroupPrefetch < end) in.goals.prefetch(row + kGroupPrefetch);
      RowDecision{in, out, checkEvery, sightEvery, chunk, query, row}.decideRow();
    }
    measureOverlaps(in.agents, in.desc.steering.maxNeighbours, begin, end, chunk);
  });
}

bool insideRegion(const PointDesc& point, float x, float y) {
  if (point.polygon.empty()) {
    const float dx = x - point.position.x, dy = y - point.position.y;
    return dx * dx + dy * dy <= point.radius * point.radius;
  }
  return core::pointInPolygon(point.polygon, core::Vec2{x, y});
}

}  // namespace throng::sim

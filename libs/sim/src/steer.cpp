// steer — preferred velocity along the path (walk to the next corner at the desired speed, relaxed
// over steering.accelerationTime), then ORCA against the neighbours from `sense` and the nearby
// walls (parallel; each agent writes only prefVel/newVel and its corner index of its own row).
// With a partition set (partition.hpp) this rank steers only the rows it owns.
#include <algorithm>
#include <cmath>

#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Distance at which a path corner counts as passed [m].
constexpr float kCornerReach = 0.5f;
/// Corners looked ahead for one in sight on multi-level worlds (see steerRow).
constexpr std::uint32_t kLevelLookAhead = 3;
/// Approaching a stop (action point, last goal), agents slow down over this time [s].
constexpr float kArrivalTime = 0.5f;
/// Members catching up with their group may walk this much faster than the group's speed.
constexpr float kFormationSpeedUp = 1.25f;
/// Relationship (i) of Musse et al. §3.2.1: when two agents meet head on, the one with lower
/// priority (smaller group, then higher group id) changes its path: it takes this share of the
/// avoidance instead of half.
constexpr float kYieldResponsibility = 0.8f;
/// Neighbours considered by the cheap steering used far from every viewer (multiresolution).
constexpr std::size_t kLodNeighbours = 4;

/// An agent that wanted to walk but barely moved for this long tries to get out of a deadlock [s].
constexpr float kStuckPatience = 1.0f;
/// Length of one deadlock-breaking attempt [s]; each attempt draws a new direction.
constexpr float kStuckAttempt = 0.8f;

/// Deadlock breaking (ORCA is symmetric: two agents wedged in a door mouth wait for each other
/// forever). A stuck agent turns its desired velocity aside or back for a moment; the turn is drawn
/// from (seed, id, attempt), so two wedged agents almost never choose mirror-image moves.
core::Vec2 unstick(core::Vec2 desired, std::uint64_t seed, std::uint32_t id, float stuckTime) {
  const auto attempt = static_cast<std::uint64_t>((stuckTime - kStuckPatience) / kStuckAttempt);
  const std::uint64_t h = core::mix64(seed ^ core::mix64((static_cast<std::uint64_t>(id) << 16) ^ attempt));
  // Angles of ±100° (aside and a little back) or 180° (step back), at half speed.
  static constexpr float kCos[3] = {-0.17364818f, -0.17364818f, -1.0f};
  static constexpr float kSin[3] = {0.98480775f, -0.98480775f, 0.0f};
  const std::size_t k = h % 3;
  return core::Vec2{desired.x * kCos[k] - desired.y * kSin[k], desired.x * kSin[k] + desired.y * kCos[k]} * 0.5f;
}

/// Two centres in the same spot give ORCA no direction to push apart; pick one from the pair's ids
/// (opposite for the two agents, so they separate).
core::Vec2 separationAxis(std::uint32_t self, std::uint32_t other) {
  const std::uint32_t lo = std::min(self, other), hi = std::max(self, other);
  const std::uint64_t h = core::mix64((static_cast<std::uint64_t>(lo) << 32) | hi);
  const float angle = static_cast<float>(h % 6283u) * 0.001f;
  const float sign = self < other ? 1.0f : -1.0f;
  return core::Vec2{std::cos(angle), std::sin(angle)} * (1e-4f * sign);
}

}  // namespace

void World::Impl::steer(const core::TaskSystem& tasks) {
  if (exchange != nullptr) {
    // Partitioned (partition.cpp): only the rows this rank owns; exchangeSteer brings the rest.
    assignOwners();
    const std::size_t owned = ownedRows.size();
    tasks.parallelFor(owned, grainFor(owned, tasks), [&](std::size_t begin, std::size_t end) {
      WorkerScratch& ws = worker(tasks);
      for (std::size_t i = begin; i < end; ++i) steerRow(ownedRows[i], ws);
    });
    return;
  }
  const std::size_t n = agents.size();
  tasks.parallelFor(n, grainFor(n, tasks), [&](std::size_t begin, std::size_t end) {
    WorkerScratch& ws = worker(tasks);
    for (std::size_t row = begin; row < end; ++row) steerRow(row, ws);
  });
}

void World::Impl::steerRow(std::size_t row, WorkerScratch& ws) {
  const SteeringDesc& s = desc.steering;
  const float dtLocal = desc.dt;
  const float relax = std::min(1.0f, dtLocal / std::max(dtLocal, s.accelerationTime));
  const std::size_t k = s.maxNeighbours;
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  const core::Vec2 vel{agents.velX[row], agents.velY[row]};
  const float maxSpeed = agents.speed[row];

  // 1. Desired velocity.
  core::Vec2 desired;
  if (agents.goalState[row] == GoalState::Seeking || (agents.goalState[row] == GoalState::Scripted && agents.scriptWalking(row))) {
    CornerPath& corners = agents.corners[row];
    std::uint32_t& ci = corners.index;
    const core::Vec2 target{agents.targetX[row], agents.targetY[row]};
    // Move on to the next corner once near this one — but only if the next is in line of sight:
    // skipping a corner of a wall before rounding it walks straight into the wall.
    if (!agents.levels) {
      while (ci + 1 < corners.size() && core::lengthSq(corners[ci] - pos) < kCornerReach * kCornerReach &&
             ws.query->visible(pos, corners[ci + 1])) {
        ++ci;
      }
    } else {
      // Multi-level worlds: where a ramp or stair meets a floor the path turns through a chain of
      // corners a few centimetres apart, and an agent that cuts across the junction is past the
      // next one, which it then cannot see from its floor: look up to kLevelLookAhead corners ahead.
      const float z = agents.posZ[row];
      while (ci + 1 < corners.size() && core::lengthSq(corners[ci] - pos) < kCornerReach * kCornerReach) {
        std::uint32_t next = ci;
        for (std::uint32_t k = ci + 1; k < corners.size() && k <= ci + kLevelLookAhead; ++k) {
          if (ws.query->visible(pos, z, corners[k])) {
            next = k;
            break;
          }
        }
        if (next == ci) break;
        ci = next;
      }
    }
    const core::Vec2 aim = ci < corners.size() ? corners[ci] : target;
    const core::Vec2 toAim = aim - pos;
    const float dist = core::length(toAim);
    if (dist > 1e-4f) {
      float v = maxSpeed;
      const bool lastLeg = ci + 1 >= corners.size();
      const PopulationDesc& pop = desc.populations[agents.population[row]];
      const std::uint32_t cursor = agents.goalCursor[row];
      const bool stopsThere = cursor >= pop.goals.size()
                                  ? !pop.wander
                                  : (desc.points[pop.goals[cursor]].kind == PointKind::Action && desc.points[pop.goals[cursor]].stop);
      if (lastLeg && (stopsThere || agents.dynamicTarget[row])) v = std::min(v, dist / kArrivalTime);
      desired = toAim * (v / dist);
      // Flocking: the group pass's correction toward the member's slot beside the others.
      desired += agents.formVel(row);
      const float cap = maxSpeed * kFormationSpeedUp;
      if (core::lengthSq(desired) > cap * cap) desired = core::normalize(desired) * cap;
      if (agents.stuckTime[row] > kStuckPatience) desired = unstick(desired, desc.seed, agents.id[row], agents.stuckTime[row]);
    }
  }
  const core::Vec2 pref = vel + (desired - vel) * relax;
  agents.prefVelX[row] = pref.x;
  agents.prefVelY[row] = pref.y;

  // 2. ORCA: walls first (hard), then neighbours. Far from every viewer (multiresolution,
  // §3.2.4) fewer neighbours and no wall half-planes: the navmesh still keeps agents inside.
  bool cheap = false;
  if (s.lodDistance > 0.0f && !viewers.empty()) {
    float nearest = 1e30f;
    for (const core::Vec2& v : viewers) nearest = std::min(nearest, core::lengthSq(v - pos));
    cheap = nearest > s.lodDistance * s.lodDistance;
  }
  auto& lines = ws.lines;
  lines.clear();
  const float wallReach = s.timeHorizonObstacle * maxSpeed + kWallMargin;
  ws.wallIds.clear();
  if (!cheap) walls.query(pos.x, pos.y, wallReach, ws.wallIds);
  for (std::uint32_t w : ws.wallIds) {
    if (agents.levels && !walls.onLevel(w, pos, agents.posZ[row])) continue;  // another floor's edge
    const core::Segment& seg = walls.segments()[w];
    OrcaLine line;
    if (segmentOrcaLine(seg.a - pos, seg.b - pos, vel, kWallMargin, s.timeHorizonObstacle, maxSpeed, line)) {
      lines.push_back(line);
    }
  }
  const std::size_t numWallLines = lines.size();
  const std::uint32_t* nb = &agents.neighbours[row * k];
  const std::size_t count = cheap ? std::min<std::size_t>(agents.neighbourCount[row], kLodNeighbours) : agents.neighbourCount[row];
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t o = nb[i];
    core::Vec2 relPos{agents.posX[o] - pos.x, agents.posY[o] - pos.y};
    if (core::lengthSq(relPos) < 1e-10f) relPos = separationAxis(agents.id[row], agents.id[o]);
    const core::Vec2 otherVel{agents.velX[o], agents.velY[o]};
    const core::Vec2 relVel = vel - otherVel;
    float responsibility = 0.5f;
    // Head on: velocities more than 120° apart (cos < -0.5), tested without square roots.
    const float d = core::dot(vel, otherVel);
    if (d < 0.0f && d * d > 0.25f * core::lengthSq(vel) * core::lengthSq(otherVel) && agents.group[row] != agents.group[o]) {
      const bool yields = agents.groupSize[row] != agents.groupSize[o] ? agents.groupSize[row] < agents.groupSize[o]
                                                                        : agents.group[row] > agents.group[o];
      responsibility = yields ? kYieldResponsibility : 1.0f - kYieldResponsibility;
    }
    lines.push_back(agentOrcaLine(relPos, relVel, vel, agents.radius[row] + agents.radius[o], s.timeHorizon, dtLocal,
                                  responsibility));
  }
  const core::Vec2 v = solveOrca(lines, numWallLines, maxSpeed, pref, ws.projected);
  agents.newVelX[row] = v.x;
  agents.newVelY[row] = v.y;
}

}  // namespace throng::sim

// steer — the preferred velocity of every agent, then its avoidance model (parallel; each agent
// writes only its own row). Reads positions, velocities, paths (corners), targets, goal state,
// formation corrections, stuck times, the neighbours from `sense` and the walls; writes prefVel,
// the corner index, and newVel (through the population's OperationalModel, models/): steer(SteerInput,
// SteerOutput), phases.hpp, whose contexts World::Impl builds (world.cpp). With a partition set
// (partition.hpp) this rank steers only the rows it owns.
//
// The preferred velocity: walk to the next corner of the path at the desired speed (slowing down
// over steering.arrivalTime before a stop), plus the group's formation correction, turned aside
// while the agent is stuck (deadlock breaking). On stairs (multi-level worlds: the navmesh's stair
// area, nav::kStairArea) the desired speed is the population's stair factor, up or down, of the
// flat one along the slope: horizontally, times cos of the slope walked. In smoke (scenario key
// "smoke", flat worlds) it is smokeSpeedFactor of the densest smoke the agent stands in. How fast an agent takes it up is the model's
// business: ORCA relaxes towards it over steering.accelerationTime, the first-order models turn
// over their reaction time.
#include <algorithm>
#include <cmath>

#include "phases.hpp"
#include "throng/core/assert.hpp"

namespace throng::sim {
namespace {

/// Deadlock breaking (ORCA is symmetric: two agents wedged in a door mouth wait for each other
/// forever). A stuck agent turns its desired velocity aside or back for a moment; the turn is drawn
/// from (seed, id, attempt), so two wedged agents almost never choose mirror-image moves.
core::Vec2 unstick(core::Vec2 desired, const SteeringDesc& s, std::uint64_t seed, std::uint32_t id, float stuckTime) {
  const auto attempt = static_cast<std::uint64_t>((stuckTime - s.stuckPatience) / s.stuckAttempt);
  const std::uint64_t h = core::mix64(seed ^ core::mix64((static_cast<std::uint64_t>(id) << 16) ^ attempt));
  // Angles of ±100° (aside and a little back) or 180° (step back), at half speed.
  static constexpr float kCos[3] = {-0.17364818f, -0.17364818f, -1.0f};
  static constexpr float kSin[3] = {0.98480775f, -0.98480775f, 0.0f};
  const std::size_t k = h % 3;
  return core::Vec2{desired.x * kCos[k] - desired.y * kSin[k], desired.x * kSin[k] + desired.y * kCos[k]} * 0.5f;
}

/// One row's preferred velocity (writes its prefVel and corner index only).
struct PreferredVelocity {
  const SteerInput& in;
  const SteerOutput& out;
  WorkerScratch& ws;

  void compute(std::size_t row) const;
  /// The factor of the desired horizontal speed for walking in direction `dir` (unit) from where
  /// the agent stands: 1 on level ground, the stair factor × cos(slope walked) on stairs.
  [[nodiscard]] float groundFactor(std::size_t row, core::Vec2 dir) const;
  /// Moves on along the path's corners once near the current one and the next is in sight.
  void advanceCorner(std::size_t row, core::Vec2 pos) const;
};

void PreferredVelocity::advanceCorner(std::size_t row, core::Vec2 pos) const {
  const SteeringDesc& s = in.steering;
  CornerPath& corners = out.corners[row];
  std::uint32_t& ci = corners.index;
  const float reach2 = s.cornerReach * s.cornerReach;
  // Move on to the next corner once near this one — but only if the next is in line of sight:
  // skipping a corner of a wall before rounding it walks straight into the wall.
  if (in.posZ.empty()) {
    // Pushed back out of sight of the corner it walks to — someone who had seen past a door's jamb
    // is pushed back behind the wall by the crowd at the door — a walker turns back to the corner
    // before, if it sees that one: else it walks into the wall and the navmesh slides it along,
    // away from the door (the dense room's walk-back, docs/validation.md). Looked at only near the
    // corner passed, and when last tick's step did not head for the aim (cheap: no sight line for
    // those walking on).
    if (ci > 0 && ci < corners.size() && core::lengthSq(corners[ci - 1] - pos) < 4.0f * reach2) {
      const core::Vec2 vel{in.model.agents.velX[row], in.model.agents.velY[row]};
      if (!onCourse(vel, corners[ci] - pos) && !ws.query->visible(pos, corners[ci]) && ws.query->visible(pos, corners[ci - 1])) --ci;
    }
    while (ci + 1 < corners.size() && core::lengthSq(corners[ci] - pos) < reach2 && ws.query->visible(pos, corners[ci + 1])) {
      ++ci;
    }
    return;
  }
  // Multi-level worlds: where a ramp or stair meets a floor the path turns through a chain of
  // corners a few centimetres apart, and an agent that cuts across the junction is past the next
  // one, which it then cannot see from its floor: look up to steering.levelLookAhead corners ahead.
  const float z = in.posZ[row];
  while (ci + 1 < corners.size() && core::lengthSq(corners[ci] - pos) < reach2) {
    std::uint32_t next = ci;
    for (std::uint32_t k = ci + 1; k < corners.size() && k <= ci + s.levelLookAhead; ++k) {
      if (ws.query->visible(pos, z, corners[k])) {
        next = k;
        break;
      }
    }
    if (next == ci) break;
    ci = next;
  }
}

float PreferredVelocity::groundFactor(std::size_t row, core::Vec2 dir) const {
  if (in.posZ.empty()) {
    // A flat world has no stairs; smoke slows walking (the densest smoke the agent stands in).
    float k = 0.0f;
    for (const SmokeDesc& smoke : in.model.desc.smoke) {
      if (smoke.extinction > k && core::pointInPolygon(smoke.polygon, {in.posX[row], in.posY[row]})) k = smoke.extinction;
    }
    return k > 0.0f ? smokeSpeedFactor(k) : 1.0f;
  }
  const nav::Surface ground = ws.query->mesh().surface(in.polyRef[row]);
  if (!ground.stair) return 1.0f;
  // RiMEA and the stair data measure speed along the slope; agents move in the plane.
  const float rise = core::dot(ground.gradient, dir);  // per horizontal metre, > 0 uphill
  const PopulationDesc& pop = in.populations[in.population[row]];
  return (rise > 0.0f ? pop.stairUp : pop.stairDown) / std::sqrt(1.0f + rise * rise);
}

/// People queuing for a lift or an escalator shuffle toward where people step on no faster than
/// this [m/s] (vertical_transport.cpp): the queue creeps, it does not rush the comb plate.
constexpr float kQueueSpeed = 0.5f;

void PreferredVelocity::compute(std::size_t row) const {
  const SteeringDesc& s = in.steering;
  const core::Vec2 pos{in.posX[row], in.posY[row]};
  const float maxSpeed = in.speed[row];
  const bool scriptWalking = !in.scriptWalk.empty() && in.scriptWalk[row] != 0;
  // Queuing for a lift or an escalator (vertical_transport.cpp): pressing on toward where people step on.
  const bool queuing = in.goalState[row] == GoalState::Riding && in.model.agents.mode[row] == AgentMode::Walking;
  core::Vec2 desired;
  if (in.goalState[row] == GoalState::Seeking || (in.goalState[row] == GoalState::Scripted && scriptWalking) || queuing) {
    advanceCorner(row, pos);
    const CornerPath& corners = out.corners[row];
    const std::uint32_t ci = corners.index;
    const core::Vec2 target{in.targetX[row], in.targetY[row]};
    const core::Vec2 aim = ci < corners.size() ? corners[ci] : target;
    const core::Vec2 toAim = aim - pos;
    const float dist = core::length(toAim);
    if (dist > 1e-4f) {
      const float walk = maxSpeed * groundFactor(row, toAim / dist);
      float v = walk;
      const bool lastLeg = ci + 1 >= corners.size();
      const bool stops = lastLeg && (queuing || stopsAtGoal(in.goals, in.points, in.populations[in.population[row]], row) ||
                                     in.dynamicTarget[row]);
      if (stops) v = std::min(v, dist / s.arrivalTime);
      if (queuing) v = std::min(v, kQueueSpeed);
      desired = toAim * (v / dist);
      // Flocking: the group pass's correction toward the member's slot beside the others.
      if (!in.formVelX.empty()) desired += core::Vec2{in.formVelX[row], in.formVelY[row]};
      const float cap = walk * s.formationSpeedUp;
      if (core::lengthSq(desired) > cap * cap) desired = core::normalize(desired) * cap;
      if (in.stuckTime[row] > s.stuckPatience) desired = unstick(desired, s, in.seed, in.id[row], in.stuckTime[row]);
    }
  }
  out.prefVelX[row] = desired.x;
  out.prefVelY[row] = desired.y;
}

}  // namespace

void steer(const SteerInput& in, const SteerOutput& out, const core::TaskSystem& tasks) {
  const RowRange all = in.rows;
  const std::size_t n = all.end;
  const auto modelOf = [&](std::size_t row) { return in.populations[in.population[row]].model.kind; };
  tasks.parallelFor(n, phaseGrain(n, tasks), [&](std::size_t begin, std::size_t end) {
    const auto worker = static_cast<std::size_t>(tasks.workerIndex());
    THRONG_ASSERT(worker < out.workers.size());
    WorkerScratch& ws = out.workers[worker];
    const RowRange rows{all.list, begin, end};
    const PreferredVelocity preferred{in, out, ws};
    for (std::size_t i = begin; i < end; ++i) {
      if (i + kGroupPrefetch < end) in.goals.prefetch(rows.row(i + kGroupPrefetch));
      preferred.compute(rows.row(i));
    }
    // Runs of consecutive rows whose populations walk with the same model: one call each.
    for (std::size_t i = begin; i < end;) {
      const ModelKind kind = modelOf(rows.row(i));
      std::size_t j = i + 1;
      while (j < end && modelOf(rows.row(j)) == kind) ++j;
      const auto m = static_cast<std::size_t>(kind);
      in.models[m]->computeVelocities(in.model, RowRange{all.list, i, j}, *ws.modelScratch[m], out.newVel);
      i = j;
    }
  });
}

}  // namespace throng::sim

// steer — the preferred velocity of every agent, then its avoidance model (parallel; each agent
// writes only its own row). Reads positions, velocities, paths (corners), targets, goal state,
// formation corrections, stuck times, the neighbours from `sense` and the walls; writes prefVel,
// the corner index, and newVel (through the population's OperationalModel, models/). With a
// partition set (partition.hpp) this rank steers only the rows it owns.
//
// The preferred velocity: walk to the next corner of the path at the desired speed (slowing down
// over steering.arrivalTime before a stop), plus the group's formation correction, turned aside
// while the agent is stuck (deadlock breaking). How fast an agent takes it up is the model's
// business: ORCA relaxes towards it over steering.accelerationTime, the first-order models turn
// over their reaction time.
#include <algorithm>
#include <cmath>

#include "world_impl.hpp"

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

}  // namespace

void World::Impl::steer(const core::TaskSystem& tasks) {
  // Partitioned (partition.cpp): only the rows this rank owns; exchangeSteer brings the rest.
  const bool partitioned = partition.exchange != nullptr;
  if (partitioned) assignOwners();
  const std::uint32_t* list = partitioned ? partition.ownedRows.data() : nullptr;
  const std::size_t n = partitioned ? partition.ownedRows.size() : agents.size();
  const ModelInput input{agents, walls, desc, viewers};
  const VelocityOutput out{agents.newVelX, agents.newVelY};
  tasks.parallelFor(n, grainFor(n, tasks), [&](std::size_t begin, std::size_t end) {
    WorkerScratch& ws = worker(tasks);
    const RowRange rows{list, begin, end};
    for (std::size_t i = begin; i < end; ++i) preferredVelocity(rows.row(i), ws);
    // Runs of consecutive rows whose populations walk with the same model: one call each.
    for (std::size_t i = begin; i < end;) {
      const ModelKind kind = modelOf(rows.row(i));
      std::size_t j = i + 1;
      while (j < end && modelOf(rows.row(j)) == kind) ++j;
      const auto m = static_cast<std::size_t>(kind);
      models[m]->computeVelocities(input, RowRange{list, i, j}, *ws.modelScratch[m], out);
      i = j;
    }
  });
}

void World::Impl::configureModels() {
  for (const PopulationDesc& pop : desc.populations) {
    const auto m = static_cast<std::size_t>(pop.model.kind);
    if (!models[m]) models[m] = makeModel(pop.model.kind);
  }
  for (auto& model : models) {
    if (model) model->configure(desc);
  }
  for (WorkerScratch& ws : scratch) addModelScratch(ws);
}

void World::Impl::addModelScratch(WorkerScratch& ws) const {
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (models[m] && !ws.modelScratch[m]) ws.modelScratch[m] = models[m]->makeScratch();
  }
}

void World::Impl::advanceCorner(std::size_t row, core::Vec2 pos, WorkerScratch& ws) {
  const SteeringDesc& s = desc.steering;
  CornerPath& corners = agents.corners[row];
  std::uint32_t& ci = corners.index;
  const float reach2 = s.cornerReach * s.cornerReach;
  // Move on to the next corner once near this one — but only if the next is in line of sight:
  // skipping a corner of a wall before rounding it walks straight into the wall.
  if (!agents.levels) {
    while (ci + 1 < corners.size() && core::lengthSq(corners[ci] - pos) < reach2 && ws.query->visible(pos, corners[ci + 1])) {
      ++ci;
    }
    return;
  }
  // Multi-level worlds: where a ramp or stair meets a floor the path turns through a chain of
  // corners a few centimetres apart, and an agent that cuts across the junction is past the next
  // one, which it then cannot see from its floor: look up to steering.levelLookAhead corners ahead.
  const float z = agents.posZ[row];
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

void World::Impl::preferredVelocity(std::size_t row, WorkerScratch& ws) {
  const SteeringDesc& s = desc.steering;
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  const float maxSpeed = agents.speed[row];
  core::Vec2 desired;
  if (agents.goalState[row] == GoalState::Seeking || (agents.goalState[row] == GoalState::Scripted && agents.scriptWalking(row))) {
    advanceCorner(row, pos, ws);
    const CornerPath& corners = agents.corners[row];
    const std::uint32_t ci = corners.index;
    const core::Vec2 target{agents.targetX[row], agents.targetY[row]};
    const core::Vec2 aim = ci < corners.size() ? corners[ci] : target;
    const core::Vec2 toAim = aim - pos;
    const float dist = core::length(toAim);
    if (dist > 1e-4f) {
      float v = maxSpeed;
      const bool lastLeg = ci + 1 >= corners.size();
      if (lastLeg && (stopsAtGoal(row) || agents.dynamicTarget[row])) v = std::min(v, dist / s.arrivalTime);
      desired = toAim * (v / dist);
      // Flocking: the group pass's correction toward the member's slot beside the others.
      desired += agents.formVel(row);
      const float cap = maxSpeed * s.formationSpeedUp;
      if (core::lengthSq(desired) > cap * cap) desired = core::normalize(desired) * cap;
      if (agents.stuckTime[row] > s.stuckPatience) desired = unstick(desired, s, desc.seed, agents.id[row], agents.stuckTime[row]);
    }
  }
  agents.prefVelX[row] = desired.x;
  agents.prefVelY[row] = desired.y;
}

}  // namespace throng::sim

// integrate — commits the ORCA velocities: each agent moves by v·dt along the navmesh surface
// (Detour's moveAlongSurface: nobody crosses a wall, whatever ORCA decided), its velocity becomes
// the displacement actually made, its heading turns toward its motion, and walking distance and
// time are summed per chunk (combined in chunk order by emit).
#include <algorithm>
#include <cmath>

#include "throng/core/assert.hpp"
#include "throng/sim/animation.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Time constant of heading changes [s]: bodies do not snap to their velocity direction.
constexpr float kTurnTime = 0.25f;
/// Below this speed the heading stays as it is [m/s].
constexpr float kTurnMinSpeed = 0.1f;

}  // namespace

void World::Impl::integrate(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  const std::size_t grain = grainFor(n, tasks);
  tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
    ChunkOutput& out = chunks[begin / grain];
    const nav::NavQuery& query = *worker(tasks).query;
    for (std::size_t row = begin; row < end; ++row) {
      const core::Vec2 moved = moveAlongMesh(row, query);
      countWalking(row, moved, out);
      animate(row, core::length(moved));
      turnHeading(row, moved);
    }
  });
}

core::Vec2 World::Impl::moveAlongMesh(std::size_t row, const nav::NavQuery& query) {
  // Reads newVel (the model's velocity), goalState; writes pos, polyRef, posZ and vel (the
  // displacement actually made over dt).
  const float h = desc.dt;
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  core::Vec2 v{agents.newVelX[row], agents.newVelY[row]};
  if (agents.goalState[row] == GoalState::Exited) v = {};
  core::Vec2 next = pos;
  if (core::lengthSq(v) > 1e-12f) {
    nav::PolyRef ref = agents.polyRef[row];
    next = query.moveAlongSurface(pos, pos + v * h, ref);
    THRONG_ASSERT(ref <= 0xffffffffu);  // 32-bit Detour references (AgentStore::polyRef)
    agents.polyRef[row] = static_cast<std::uint32_t>(ref);
    if (agents.levels && ref != 0) agents.posZ[row] = query.heightAt(ref, next);  // stairs, ramps
  }
  const core::Vec2 moved = next - pos;
  agents.posX[row] = next.x;
  agents.posY[row] = next.y;
  agents.velX[row] = moved.x / h;
  agents.velY[row] = moved.y / h;
  return moved;
}

void World::Impl::countWalking(std::size_t row, core::Vec2 moved, ChunkOutput& out) {
  // Reads mode, goalState, speed; writes stuckTime and the chunk's walking sums.
  const float h = desc.dt;
  if (agents.mode[row] != AgentMode::Walking) {
    agents.stuckTime[row] = 0.0f;
    return;
  }
  out.walkedDistance += core::length(moved);
  out.walkingTime += h;
  // Wanting to walk (a preferred velocity) but barely moving: count toward deadlock breaking.
  const bool wants = agents.goalState[row] == GoalState::Seeking ||
                     (agents.goalState[row] == GoalState::Scripted && agents.scriptWalking(row));
  const bool stuck = wants && core::length(moved) < 0.1f * agents.speed[row] * h;
  agents.stuckTime[row] = stuck ? agents.stuckTime[row] + h : 0.0f;
}

void World::Impl::animate(std::size_t row, float step) {
  // The walk cycle advances with distance, idle with time, an action with its clock. Reads
  // goalState, the goal point's clip, the script's clip; writes animClip and animPhase.
  const float h = desc.dt;
  auto setClip = [&](std::uint16_t clip, float phase) {
    if (clip != agents.animClip[row]) {
      // A new clip starts at its beginning, except walk and idle, which keep their cycle.
      if (clip != kClipWalk && clip != kClipIdle) phase = 0.0f;
      agents.animClip[row] = clip;
    }
    agents.animPhase[row] = phase - std::floor(phase);
  };
  if (agents.goalState[row] == GoalState::Acting) {
    const std::uint32_t goal = currentGoalPoint(row);
    const std::uint32_t point = goal == kNoPoint ? 0 : goal;
    const float total = std::max(h, desc.points[point].actionDuration);
    const float left = static_cast<float>(agents.actionEndTick[row] > tick ? agents.actionEndTick[row] - tick : 0) * h;
    setClip(pointClip[point], std::clamp(1.0f - left / total, 0.0f, 0.999f));
  } else if (agents.goalState[row] == GoalState::Scripted && agents.scriptClipOf(row) != kNoClip) {
    // A micro-behaviour clip of an action script (wave, nod, ...), played once.
    const std::uint16_t clip = agents.scriptClip[row];
    const float phase = agents.animClip[row] == clip ? agents.animPhase[row] + h / commonGround.clipDuration[clip] : 0.0f;
    setClip(clip, std::min(phase, 0.999f));
  } else if (step > 0.1f * h) {
    setClip(kClipWalk, agents.animPhase[row] + step / kWalkCycleLength);
  } else {
    setClip(kClipIdle, agents.animPhase[row] + h / kIdleCycle);
  }
}

void World::Impl::turnHeading(std::size_t row, core::Vec2 moved) {
  // Bodies turn toward their motion over kTurnTime, except while acting or standing in a script.
  // Reads goalState; writes ori.
  const bool holdsHeading = agents.goalState[row] == GoalState::Acting ||
                            (agents.goalState[row] == GoalState::Scripted && !agents.scriptWalking(row));
  if (holdsHeading) return;
  const float h = desc.dt;
  const float turn = std::min(1.0f, h / kTurnTime);
  const float speed = core::length(moved) / h;
  if (!(speed > kTurnMinSpeed)) return;
  const core::Vec2 dir = moved / (speed * h);
  const core::Vec2 ori = core::normalize(core::Vec2{agents.oriX[row], agents.oriY[row]} + (dir - core::Vec2{agents.oriX[row], agents.oriY[row]}) * turn);
  if (core::lengthSq(ori) > 0.0f) {
    agents.oriX[row] = ori.x;
    agents.oriY[row] = ori.y;
  }
}

}  // namespace throng::sim

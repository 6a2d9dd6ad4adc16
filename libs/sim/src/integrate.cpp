// integrate — commits the avoidance models' velocities: each agent moves by v·dt along the navmesh
// surface (Detour's moveAlongSurface: nobody crosses a wall, whatever the model decided), its
// velocity becomes the displacement actually made, its heading turns toward its motion (toward
// where it wants to go while slower than 0.5 m/s), its animation advances, and walking distance
// and time are summed per chunk (combined in chunk order by emit). Reads IntegrateInput; writes
// IntegrateOutput (phases.hpp), each row only its own.
#include <algorithm>
#include <cmath>

#include "phases.hpp"
#include "throng/core/assert.hpp"
#include "throng/sim/animation.hpp"

namespace throng::sim {
namespace {

/// Below this speed the heading stays as it is [m/s] (when the agent wants to go nowhere).
constexpr float kTurnMinSpeed = 0.1f;

// The optional Common Ground columns read as their defaults when absent (as AgentStore's accessors).
bool scriptWalking(const IntegrateInput& in, std::size_t row) { return !in.scriptWalk.empty() && in.scriptWalk[row] != 0; }
std::uint16_t scriptClipOf(const IntegrateInput& in, std::size_t row) {
  return in.scriptClip.empty() ? kNoClip : in.scriptClip[row];
}

core::Vec2 moveAlongMesh(const IntegrateInput& in, const IntegrateOutput& out, std::size_t row,
                         const nav::NavQuery& query) {
  // Reads newVel (the model's velocity), goalState; writes pos, polyRef, posZ and vel (the
  // displacement actually made over dt).
  const float h = in.dt;
  const core::Vec2 pos{out.posX[row], out.posY[row]};
  core::Vec2 v{in.newVelX[row], in.newVelY[row]};
  // Gone, or carried by a lift or escalator (vertical_transport.cpp places those; people queuing for one
  // stand, and step aside when pressed, as anyone standing does).
  if (in.goalState[row] == GoalState::Exited || (in.goalState[row] == GoalState::Riding && in.mode[row] == AgentMode::Acting)) v = {};
  core::Vec2 next = pos;
  if (core::lengthSq(v) > 1e-12f) {
    nav::PolyRef ref = out.polyRef[row];
    next = query.moveAlongSurface(pos, pos + v * h, ref);
    THRONG_ASSERT(ref <= 0xffffffffu);  // 32-bit Detour references (AgentStore::polyRef)
    out.polyRef[row] = static_cast<std::uint32_t>(ref);
    if (!out.posZ.empty() && ref != 0) out.posZ[row] = query.heightAt(ref, next);  // stairs, ramps
  }
  const core::Vec2 moved = next - pos;
  out.posX[row] = next.x;
  out.posY[row] = next.y;
  out.velX[row] = moved.x / h;
  out.velY[row] = moved.y / h;
  return moved;
}

void countWalking(const IntegrateInput& in, const IntegrateOutput& out, std::size_t row, core::Vec2 moved,
                  ChunkOutput& chunk) {
  // Reads mode, goalState, speed; writes stuckTime and the chunk's walking sums.
  const float h = in.dt;
  if (in.mode[row] != AgentMode::Walking) {
    out.stuckTime[row] = 0.0f;
    return;
  }
  chunk.walkedDistance += core::length(moved);
  chunk.walkingTime += h;
  // Wanting to walk (a preferred velocity) but barely moving: count toward deadlock breaking.
  const bool wants = in.goalState[row] == GoalState::Seeking ||
                     (in.goalState[row] == GoalState::Scripted && scriptWalking(in, row));
  const bool stuck = wants && core::length(moved) < 0.1f * in.speed[row] * h;
  out.stuckTime[row] = stuck ? out.stuckTime[row] + h : 0.0f;
}

void animate(const IntegrateInput& in, const IntegrateOutput& out, std::size_t row, float step) {
  // The walk cycle advances with distance, idle with time, an action with its clock. Reads
  // goalState, the goal point's clip, the script's clip; writes animClip and animPhase.
  const float h = in.dt;
  auto setClip = [&](std::uint16_t clip, float phase) {
    if (clip != out.animClip[row]) {
      // A new clip starts at its beginning, except walk and idle, which keep their cycle.
      if (clip != kClipWalk && clip != kClipIdle) phase = 0.0f;
      out.animClip[row] = clip;
    }
    out.animPhase[row] = phase - std::floor(phase);
  };
  if (in.goalState[row] == GoalState::Acting) {
    const std::uint32_t goal = in.goals.currentGoalPoint(row);
    const std::uint32_t point = goal == kNoPoint ? 0 : goal;
    const float total = std::max(h, in.points[point].actionDuration);
    const float left = static_cast<float>(in.actionEndTick[row] > in.tick ? in.actionEndTick[row] - in.tick : 0) * h;
    setClip(in.pointClip[point], std::clamp(1.0f - left / total, 0.0f, 0.999f));
  } else if (in.goalState[row] == GoalState::Scripted && scriptClipOf(in, row) != kNoClip) {
    // A micro-behaviour clip of an action script (wave, nod, ...), played once.
    const std::uint16_t clip = in.scriptClip[row];
    const float phase = out.animClip[row] == clip ? out.animPhase[row] + h / in.clipDuration[clip] : 0.0f;
    setClip(clip, std::min(phase, 0.999f));
  } else if (step > 0.1f * h) {
    setClip(kClipWalk, out.animPhase[row] + step / kWalkCycleLength);
  } else {
    setClip(kClipIdle, out.animPhase[row] + h / kIdleCycle);
  }
}

void turnHeading(const IntegrateInput& in, const IntegrateOutput& out, std::size_t row, core::Vec2 moved) {
  // Bodies turn toward their motion over kTurnTime, except while acting or standing in a script.
  // Reads goalState; writes ori.
  const bool holdsHeading = in.goalState[row] == GoalState::Acting ||
                            (in.goalState[row] == GoalState::Scripted && !scriptWalking(in, row));
  if (holdsHeading) return;
  // The model found that turning would press the body into a neighbour's (avm: turnDeepens).
  if (!in.holdHeading.empty() && in.holdHeading[row] != 0) return;
  const float h = in.dt;
  const float turn = std::min(1.0f, h / kTurnTime);
  const float speed = core::length(moved) / h;
  // Slower than kFaceDesiredBelow, a body faces where it wants to go (its preferred velocity), not
  // where the crowd shoves it: people in a queue shuffle sideways and back facing the door.
  const core::Vec2 want = in.prefVelX.empty() ? core::Vec2{} : core::Vec2{in.prefVelX[row], in.prefVelY[row]};
  const float wanted = core::length(want);
  core::Vec2 dir;
  if (speed < kFaceDesiredBelow && wanted > 1e-3f) {
    dir = want / wanted;
  } else {
    if (!(speed > kTurnMinSpeed)) return;
    dir = moved / (speed * h);
  }
  const core::Vec2 ori = core::normalize(core::Vec2{out.oriX[row], out.oriY[row]} + (dir - core::Vec2{out.oriX[row], out.oriY[row]}) * turn);
  if (core::lengthSq(ori) > 0.0f) {
    out.oriX[row] = ori.x;
    out.oriY[row] = ori.y;
  }
}

}  // namespace

void integrate(const IntegrateInput& in, const IntegrateOutput& out, const core::TaskSystem& tasks) {
  const std::size_t n = out.posX.size();
  const std::size_t grain = phaseGrain(n, tasks);
  tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
    ChunkOutput& chunk = out.chunks[begin / grain];
    const auto worker = static_cast<std::size_t>(tasks.workerIndex());
    THRONG_ASSERT(worker < in.workers.size());
    const nav::NavQuery& query = *in.workers[worker].query;
    for (std::size_t row = begin; row < end; ++row) {
      const core::Vec2 moved = moveAlongMesh(in, out, row, query);
      countWalking(in, out, row, moved, chunk);
      animate(in, out, row, core::length(moved));
      turnHeading(in, out, row, moved);
    }
  });
}

}  // namespace throng::sim

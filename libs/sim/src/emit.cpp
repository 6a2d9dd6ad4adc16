// The emit phase and the frame (phases.hpp): emit merges the tick's per-chunk outputs (events,
// walking sums, meetings) in chunk order, removes the agents that exited and moves the clock on;
// takeFrame snapshots the agents with everything that happened since the last frame (events with
// the spawner's compact spawn events written out in place, Common Ground scripts and
// coordinations). leaveWorld, what an agent leaving undoes, is shared with crowd removal (insert.cpp).
#include <algorithm>
#include <vector>

#include "goals.hpp"
#include "phases.hpp"
#include "spawner.hpp"

namespace throng::sim {
namespace {

/// The chunks' events and sums, in chunk order; the chunks are emptied.
void mergeChunks(const EmitInput& in, const EmitOutput& out) {
  WorldStats& stats = out.stats;
  for (ChunkOutput& c : out.chunks) {
    for (const Event& e : c.events) {
      if (e.kind == EventKind::Exit) {
        ++stats.exited;
        stats.lastExitTime = static_cast<double>(in.tick + 1) * in.dt;
      }
    }
    out.events.insert(out.events.end(), c.events.begin(), c.events.end());
    stats.walkedDistance += c.walkedDistance;
    stats.walkingTime += c.walkingTime;
    stats.socialMeetings += c.socialMeetings;
    stats.maxOverlap = std::max(stats.maxOverlap, static_cast<double>(c.maxOverlap));
    stats.overlapAgentSteps += c.overlapping;
    c.events.clear();
    c.walkedDistance = c.walkingTime = 0.0;
    c.socialMeetings = 0;
    c.maxOverlap = 0.0f;
    c.overlapping = 0;
  }
}

/// Removes the rows of agents that exited; whether there were any.
bool removeExited(const EmitOutput& out) {
  AgentStore& agents = out.agents;
  const bool anyExit = std::any_of(agents.goalState.begin(), agents.goalState.end(),
                                   [](GoalState g) { return g == GoalState::Exited; });
  if (!anyExit) return false;
  std::vector<std::uint8_t> keep(agents.size());
  for (std::size_t r = 0; r < agents.size(); ++r) {
    keep[r] = agents.goalState[r] != GoalState::Exited;
    if (!keep[r]) leaveWorld(r, out.goals, out.groups);
  }
  agents.compact(keep);
  return true;
}

}  // namespace

void leaveWorld(std::size_t row, GoalWriter& goals, GroupTable& groups) {
  const AgentStore& agents = goals.agents;
  goals.releaseTarget(row);
  GroupState& g = groups[agents.group[row]];
  g.members.erase(agents.id[row]);
  if (g.leader == agents.id[row]) g.leader = g.members.empty() ? kNoAgent : g.members.front();
}

bool emit(const EmitInput& in, const EmitOutput& out) {
  mergeChunks(in, out);
  out.stats.agentSteps += out.agents.size();
  const bool removed = removeExited(out);
  out.stats.tick = in.tick + 1;
  out.stats.time = static_cast<double>(in.tick + 1) * in.dt;
  out.stats.active = static_cast<std::uint32_t>(out.agents.size());
  return removed;
}

FramePtr takeFrame(const FrameInput& in, const FrameOutput& out) {
  auto frame = std::make_shared<Frame>();
  const AgentStore& a = in.agents;
  frame->tick = in.tick;
  frame->time = static_cast<double>(in.tick) * in.dt;
  // Agents by ascending id: the columns as they are, or gathered when the rows are sorted spatially.
  const auto take = [&](auto& to, const auto& column) {
    if (in.idOrder.empty()) {
      to.assign(column.begin(), column.end());
      return;
    }
    to.resize(in.idOrder.size());
    for (std::size_t i = 0; i < in.idOrder.size(); ++i) to[i] = column[in.idOrder[i]];
  };
  take(frame->ids, a.id);
  take(frame->posX, a.posX);
  take(frame->posY, a.posY);
  if (a.levels) take(frame->posZ, a.posZ);
  take(frame->velX, a.velX);
  take(frame->velY, a.velY);
  take(frame->oriX, a.oriX);
  take(frame->oriY, a.oriY);
  take(frame->mode, a.mode);
  take(frame->clip, a.animClip);
  take(frame->phase, a.animPhase);
  frame->events = out.spawner.takeEvents(out.events);
  frame->script = std::move(out.commonGround.pendingScript);
  out.commonGround.pendingScript.clear();
  frame->coordinations = std::move(out.commonGround.pendingCoordinations);
  out.commonGround.pendingCoordinations.clear();
  return frame;
}

}  // namespace throng::sim
